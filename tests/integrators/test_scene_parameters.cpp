// The parameter core by name (integrators/scene_params/): the list, a parameter's numbers read
// and written back, refusals, and the gradient set-up's refusals.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/error.h"
#include "integrators/gradients/gradient_setup.h"
#include "integrators/render_scene.h"
#include "integrators/scene_params/edited_scene.h"
#include "integrators/scene_params/parameter_numbers.h"
#include "integrators/scene_params/parameter_path.h"
#include "integrators/scene_params/scene_parameter_list.h"
#include "integrators/scene_reader.h"
#include "io/scene_state_text.h"
#include "support/errors.h"

namespace nx {
namespace {

const char* kScene = R"(<scene><settings><xres>8</xres><yres>6</yres><mode>spectral_mcpt</mode>
<sampl>4</sampl><bands>400:700:50</bands></settings>
<camera><position>0,1,-4</position><look_at>0,0.5,0</look_at></camera>
<plane><normal>0,1,0</normal><distance>0</distance><material>matte</material>
<reflectance>400:0.3, 550:0.5, 700:0.8</reflectance></plane>
<sphere><center>0,0.7,0</center><radius>0.7</radius><material>matte</material>
<reflectance>0.4</reflectance><fluorescence><absorption>460</absorption><stokes>90</stokes>
</fluorescence></sphere>
<sphere><center>-1.5,2.5,-1</center><radius>0.5</radius><material>matte</material>
<reflectance>0</reflectance><emission scale="5e-3">D65</emission></sphere>
<light><position>1,3,-2</position><color>1,0.5,0.25</color></light>
</scene>)";

TEST(SceneParameters, NamesParseIntoStepsAndBadNamesAreRefused) {
  const auto s = parameterSteps("materials['card'].fluorescence.stokes_nm");
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(std::get<std::string>(s[0].index), "card");
  EXPECT_EQ(s[2].attribute, "stokes_nm");
  EXPECT_EQ(std::get<size_t>(parameterSteps("objects[12].radius")[0].index), 12u);
  for (const char* bad : {"", "objects[", "objects[1]", "objects[x].radius", "a..b", "a.", ".a",
                          "objects[-1].radius", "objects[99999999999999999999].radius"})
    EXPECT_EQ(test::errorMessage([&] { parameterSteps(bad); }),
              std::string("no scene parameter named '") + bad + "'")
        << bad;
  EXPECT_EQ(canonicalParameterName("materials[\"x\"].reflectance"), "materials['x'].reflectance");
}

TEST(SceneParameters, NumbersReadAndWrittenBack) {
  SceneDesc d = parseScene(kScene, "t.scn");
  const ParameterNumbers table = parameterNumbers(d, "objects[0].reflectance");
  EXPECT_EQ(table.form, ParameterNumbers::Form::Table);
  EXPECT_EQ(table.values, (std::vector<double>{0.3, 0.5, 0.8}));
  EXPECT_EQ(parameterNumbers(d, "objects[1].fluorescence.stokes_nm").values,
            std::vector<double>{90});
  EXPECT_EQ(parameterNumbers(d, "lights[0].color").values, (std::vector<double>{1, 0.5, 0.25, 1}));
  const double knots[] = {0.3, 0.6, 0.8};
  EXPECT_TRUE(setParameterNumbers(d, "objects[0].reflectance", knots));
  EXPECT_EQ(parameterNumbers(d, "objects[0].reflectance").values[1], 0.6);
  const double scale[] = {0.25};
  EXPECT_TRUE(setParameterNumbers(d, "objects[2].emission_scale", scale));
  EXPECT_EQ(d.objects[2].emissionScale, 0.25);
}

TEST(SceneParameters, ValuesOutsideTheirRangeAreRefusedAndLeaveTheScene) {
  SceneDesc d = parseScene(kScene, "t.scn");
  const std::string before = sceneStateText(d);
  const double negative[] = {-1}, big[] = {1e9}, nan[] = {std::nan("")};
  EXPECT_FALSE(setParameterNumbers(d, "objects[1].fluorescence.stokes_nm", negative));
  EXPECT_FALSE(setParameterNumbers(d, "objects[1].fluorescence.stokes_nm", big));
  EXPECT_FALSE(setParameterNumbers(d, "objects[1].reflectance", nan));
  const double negativeKnot[] = {0.3, -0.1, 0.8}; // spectra are not negative
  EXPECT_FALSE(setParameterNumbers(d, "objects[0].reflectance", negativeKnot));
  const double colour[] = {-1, 0, 0, 1}; // a light's colour: non-negative, no upper bound
  EXPECT_FALSE(setParameterNumbers(d, "lights[0].color", colour));
  EXPECT_EQ(sceneStateText(d), before);
  const double two[] = {1, 2};
  EXPECT_EQ(test::errorMessage([&] { setParameterNumbers(d, "objects[1].reflectance", two); }),
            "objects[1].reflectance: expected 1 numbers, found 2");
}

TEST(SceneParameters, ParametersWithoutNumbersAreRefusedByName) {
  const SceneDesc d = parseScene(kScene, "t.scn");
  EXPECT_NE(test::errorMessage([&] {
              parameterNumbers(d, "objects[2].emission");
            }).find("objects[2].emission: not differentiable as given"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([&] {
              parameterNumbers(d, "objects[1].fluorescence.width_nm");
            }).find("found None"),
            std::string::npos);
  EXPECT_EQ(test::errorMessage([&] { parameterNumbers(d, "objects[7].reflectance"); }),
            "no scene parameter named 'objects[7].reflectance' (Scene.parameters() lists them)");
}

// Every number of every example scene's differentiable parameters written back as it is
// leaves the scene's state as it was (the writer loses nothing: extrapolation, names, files).
TEST(SceneParameters, EveryExampleParameterWrittenBackAsItIsKeepsTheScene) {
  int checked = 0;
  for (const auto& entry : std::filesystem::directory_iterator(NX_SOURCE_DIR "/scenes")) {
    if (entry.path().extension() != ".scn") continue;
    SCOPED_TRACE(entry.path().filename().string());
    SceneDesc d = loadScene(entry.path().string());
    const std::string before = sceneStateText(d);
    for (const SceneParameterInfo& p : sceneParameters(d)) {
      if (!p.differentiable) continue;
      ParameterNumbers n;
      try {
        n = parameterNumbers(d, p.name);
      } catch (const Error&) {
        continue; // not given, or a name or file (refused by name, as tested above)
      }
      EXPECT_TRUE(setParameterNumbers(d, p.name, n.values)) << p.name;
      ++checked;
    }
    EXPECT_EQ(sceneStateText(d), before);
  }
  EXPECT_GT(checked, 20);
}

TEST(SceneParameters, GradientSetupRefusesByName) {
  const SceneDesc d = parseScene(kScene, "t.scn");
  const RenderScene base = buildRenderScene(d);
  auto errorOf = [&](std::vector<std::string> names) {
    return test::errorMessage([&] { gradientSetup(d, names, base, true); });
  };
  EXPECT_NE(errorOf({"objects[0].normal"}).find("objects[0].normal: not differentiated"),
            std::string::npos);
  // A shape's parameter is differentiated, but not an emitter's (its light samples would move).
  EXPECT_EQ(gradientSetup(d, {"objects[1].center"}, base, true).tangents.slots(), 3u);
  EXPECT_NE(errorOf({"objects[2].radius"}).find("objects[2].radius: moving an emitter"),
            std::string::npos);
  EXPECT_NE(errorOf({"camera.up"}).find("camera.up: not differentiated"), std::string::npos);
  EXPECT_EQ(errorOf({"objects[1].reflectance", "objects[1].reflectance"}),
            "gradients: 'objects[1].reflectance' given twice");
  EXPECT_EQ(errorOf({}), "gradients: expected at least one name");
  // A value at the end of its range is differenced one-sidedly: 0 reflectance.
  const GradientSetup s =
      gradientSetup(d, {"objects[2].reflectance", "objects[0].reflectance"}, base, true);
  ASSERT_EQ(s.parameters.size(), 2u);
  EXPECT_EQ(s.parameters[1].firstSlot, 1u);
  EXPECT_EQ(s.parameters[1].slots, 3u);
  EXPECT_TRUE(s.parameters[1].indexed);
  EXPECT_EQ(s.tangents.slots(), 4u);
}

TEST(SceneFields, EveryListedFieldReadsAndWritesBackUnchanged) {
  EditedScene e;
  e.desc = parseScene(kScene, "t.scn");
  const std::string before = sceneStateText(e.desc);
  int fields = 0;
  for (const SceneParameterInfo& p : sceneParameters(e.desc)) {
    if (sceneFieldKey(p.name).empty()) continue;
    SCOPED_TRACE(p.name);
    const FieldValue v = sceneField(e.desc, p.name);
    // What may be None stays None; the rest is written back as read.
    if (std::holds_alternative<std::monostate>(v) &&
        (p.name == "camera.intrinsics" || p.name == "camera.extrinsics" ||
         p.name.ends_with("_nm") || p.name.ends_with("matrix")))
      continue;
    e.setField(p.name, v, "as read");
    ++fields;
  }
  EXPECT_EQ(sceneStateText(e.desc), before);
  EXPECT_EQ(e.edits.size(), static_cast<size_t>(fields));
  EXPECT_GT(fields, 20);
  EXPECT_EQ(e.edits.front(), "resolution = as read");
}

TEST(SceneFields, SetByNameIsCheckedInItsPlace) {
  SceneDesc d = parseScene(kScene, "t.scn");
  const std::string before = sceneStateText(d);
  auto errorOf = [&](const std::string& name, const FieldValue& v) {
    return test::errorMessage([&] { setSceneField(d, name, v); });
  };
  EXPECT_EQ(errorOf("spp", 0.0), "spp: expected an int in [1, 1073741824], found 0");
  EXPECT_EQ(errorOf("resolution", std::vector<double>{0, 10}),
            "resolution: expected sizes in [1, 65536], found 0");
  EXPECT_EQ(errorOf("mode", std::string("fast")),
            "mode: expected rt, mcpt or spectral_mcpt, found 'fast'");
  EXPECT_EQ(errorOf("objects[0].emission_scale", 2.0),
            "objects[0].emission_scale: the object emits no light");
  EXPECT_EQ(errorOf("objects[2].emission_quantity", std::string("irradiance")),
            "objects[2].emission_quantity: 'irradiance' needs a distance: set emission_at");
  EXPECT_EQ(errorOf("objects[1].fluorescence.stokes_nm", FieldValue()),
            "objects[1].fluorescence.stokes_nm: expected a number (the model has no default), "
            "found None");
  EXPECT_THROW(setSceneField(d, "objects[1].fluorescence.stokes_nm", FieldValue()), FieldTypeError);
  EXPECT_NE(errorOf("camera.up", Vec3d(0, 0, 0)).find("camera.up: "), std::string::npos);
  EXPECT_EQ(errorOf("objects[9].emission", FieldValue()),
            "no scene parameter named 'objects[9].emission' (Scene.parameters() lists them)");
  EXPECT_EQ(sceneStateText(d), before); // every refusal left the scene as it was

  setSceneField(d, "camera.intrinsics", std::vector<double>{8, 8, 4, 3});
  EXPECT_TRUE(std::holds_alternative<std::monostate>(sceneField(d, "camera.fov")));
  setSceneField(d, "camera.fov", 50.0); // the field of view replaces the intrinsics
  EXPECT_FALSE(d.camera.intrinsics);
  setSceneField(d, "camera.extrinsics", std::vector<double>{1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 4});
  EXPECT_EQ(errorOf("camera.position", Vec3d(0, 0, 1)),
            "camera.position: the camera is placed by <extrinsics>");
  setSceneField(d, "objects[2].emission_at", 2.0);
  setSceneField(d, "objects[2].emission_quantity", std::string("flux"));
  EXPECT_FALSE(d.objects[2].emissionAt);
  EXPECT_TRUE(d.objects[2].emissionFlux);
  setSceneField(d, "objects[1].fluorescence.absorption_nm", 470.0);
  EXPECT_EQ(*d.objects[1].params.get<FluorescenceDesc>("fluorescence")->absorptionNm, 470);
}

} // namespace
} // namespace nx
