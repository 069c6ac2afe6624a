// The material kinds' registry against the scene format: every kind's schema is consistent
// with the declared parameters, every parameter a kind takes builds, every one it does not
// take is refused at its own line, and materials are shared exactly when their canonical
// parameters are equal. The cases are generated from the registry, so a new kind or a new
// parameter is covered without editing this file.

#include <gtest/gtest.h>

#include <cstdlib>
#include <set>

#include "core/params/material_parameters.h"
#include "integrators/materials/material_kind.h"
#include "integrators/render_scene.h"
#include "integrators/scene_reader.h"
#include "support/errors.h"
#include "support/render_checks.h"

namespace nx {
namespace {

const std::string kSettings = "<xres>4</xres><yres>4</yres><mode>spectral_mcpt</mode>";
const std::string kCamera = "<position>0,0,-5</position><look_at>0,0,0</look_at>";

// One parameter element with the declared example value.
std::string element(const ParamSpec& spec, const std::string& value = "") {
  return std::string("<") + spec.name + ">" + (value.empty() ? spec.example : value) + "</" +
         spec.name + ">";
}

// The parameters a kind needs besides `param` to build: a conductor its metal (or eta and k
// together), anisotropic roughness both directions.
std::string companions(const MaterialKindSpec& kind, const std::string& param) {
  std::string out;
  auto add = [&](const char* name) {
    if (param != name && kind.param(name)) out += element(*materialParameter(name));
  };
  if (std::string(kind.name) == "conductor") {
    if (param == "eta") add("k");
    if (param == "k") add("eta");
    if (param != "eta" && param != "k") add("metal");
  }
  if (param == "alpha_u") add("alpha_v");
  if (param == "alpha_v") add("alpha_u");
  // A surface with a diffuse base (the kinds that take <fluorescence>: mixtures, coated,
  // rough matte) that does not emit needs an albedo.
  if (kind.param("fluorescence")) add("reflectance");
  return out;
}

std::string sphere(const MaterialKindSpec& kind, const std::string& parameters,
                   const std::string& center = "0,0,0") {
  return "<sphere><center>" + center + "</center><radius>1</radius><material>" +
         std::string(kind.name) + "</material>" + parameters + "</sphere>";
}

TEST(MaterialKinds, RegistryAgreesWithTheDeclaredParameters) {
  std::set<std::string> names, taken;
  for (const MaterialKindSpec* kind : materialKinds()) {
    SCOPED_TRACE(kind->name);
    EXPECT_TRUE(names.insert(kind->name).second) << "a kind registered twice";
    EXPECT_EQ(findMaterialKind(kind->name), kind);
    EXPECT_NE(kind->build, nullptr);
    EXPECT_GT(std::string(kind->doc).size(), 10u);
    for (const KindParameter& p : kind->params) {
      const ParamSpec* spec = materialParameter(p.name);
      ASSERT_NE(spec, nullptr) << p.name << " is not a declared material parameter";
      taken.insert(p.name);
      // A number default lies in the declared range.
      if (spec->type == ParamType::Number && *p.defaultText) {
        EXPECT_TRUE(spec->range->contains(kind->numberDefault(p.name))) << p.name;
      }
    }
    for (const auto& [param, why] : kind->refusals) {
      EXPECT_NE(materialParameter(param), nullptr) << param;
      EXPECT_EQ(kind->param(param), nullptr) << param << " is both taken and refused";
    }
  }
  for (const ParamSpec& spec : materialParameters())
    EXPECT_TRUE(taken.count(spec.name)) << spec.name << " is declared but no kind takes it";
  EXPECT_EQ(findMaterialKind("velvet"), nullptr);
}

TEST(MaterialKinds, EveryParameterAKindTakesBuilds) {
  for (const MaterialKindSpec* kind : materialKinds())
    for (const KindParameter& p : kind->params) {
      SCOPED_TRACE(std::string(kind->name) + " <" + p.name + ">");
      const std::string body =
          sphere(*kind, element(*materialParameter(p.name)) + companions(*kind, p.name));
      const std::string message = test::errorMessage([&] {
        (void)resolveRenderScene(parseScene(sceneText(kSettings, kCamera, body), "t.scn"));
      });
      EXPECT_EQ(message, "no error") << body;
    }
}

// Mitsuba 3's "unreferenced property": a parameter the kind does not take is an error at its
// own line, naming what the kind takes.
TEST(MaterialKinds, EveryParameterAKindDoesNotTakeIsRefusedAtItsLine) {
  int cases = 0;
  for (const MaterialKindSpec* kind : materialKinds())
    for (const ParamSpec& spec : materialParameters()) {
      if (kind->param(spec.name)) continue;
      SCOPED_TRACE(std::string(kind->name) + " <" + spec.name + ">");
      const std::string text = "<scene>\n<settings>" + kSettings + "</settings>\n<camera>" +
                               kCamera + "</camera>\n<sphere><center>0,0,0</center>" +
                               "<radius>1</radius><material>" + kind->name + "</material>\n" +
                               element(spec) + "\n</sphere>\n</scene>\n";
      const std::string message = test::errorMessage([&] { (void)parseScene(text, "t.scn"); });
      EXPECT_EQ(message.rfind("t.scn:5: expected ", 0), 0u) << message;
      EXPECT_NE(message.find(std::string(" on ") + kind->name + ", found <" + spec.name + ">"),
                std::string::npos)
          << message;
      // The same through a <material id> definition.
      const std::string named = "<scene>\n<settings>" + kSettings + "</settings>\n<camera>" +
                                kCamera + "</camera>\n<material id=\"m\" type=\"" + kind->name +
                                "\">\n" + element(spec) +
                                "</material>\n<sphere><center>0,0,0</center><radius>1</radius>"
                                "<material>m</material></sphere>\n</scene>\n";
      EXPECT_EQ(test::errorMessage([&] { (void)parseScene(named, "t.scn"); }).rfind("t.scn:5: ", 0),
                0u);
      ++cases;
    }
  EXPECT_GT(cases, 50);
}

// Two objects share a material exactly when their kinds and canonical parameters are equal:
// written in another order they share; any parameter's value changed, they do not.
TEST(MaterialKinds, MaterialsAreSharedExactlyWhenTheirParametersAreEqual) {
  // The material indices of two spheres with the same kind and the given parameters.
  auto materialsOf = [&](const MaterialKindSpec& kind, const std::string& a, const std::string& b) {
    const RenderScene s = resolveRenderScene(parseScene(
        sceneText(kSettings, kCamera, sphere(kind, a) + sphere(kind, b, "3,0,0")), "t.scn"));
    return std::pair{s.shapes(ShapeKind::Sphere)[0].material,
                     s.shapes(ShapeKind::Sphere)[1].material};
  };
  {
    const auto [ma, mb] =
        materialsOf(*findMaterialKind("conductor"), "<metal>gold</metal><alpha>0.2</alpha>",
                    "<alpha>0.2</alpha><metal>gold</metal>");
    EXPECT_EQ(ma, mb) << "the same parameters in another order";
  }
  for (const MaterialKindSpec* kind : materialKinds())
    for (const KindParameter& p : kind->params) {
      const ParamSpec& spec = *materialParameter(p.name);
      std::string changed;
      if (spec.type == ParamType::Number)
        changed = element(spec, std::to_string(0.5 * (std::atof(spec.example) + spec.range->lo)));
      else if (spec.type == ParamType::Coating)
        changed = element(spec, "<thickness>150</thickness><ior>1.41</ior>");
      else if (spec.type == ParamType::Fluorescence)
        changed = element(spec, "<absorption>450</absorption><stokes>61</stokes>");
      else if (spec.type == ParamType::Name)
        changed = element(spec, "silver");
      else if (spec.type == ParamType::Ior)
        changed = element(spec, "1.41");
      else if (spec.type == ParamType::Rgb)
        changed = element(spec, "0.8, 0.2, 0.11");
      else if (spec.type == ParamType::Spectrum)
        changed = element(spec, "1.25");
      else
        changed = element(spec, "400:0.2, 700:0.81");
      SCOPED_TRACE(std::string(kind->name) + " " + changed);
      const std::string rest = companions(*kind, p.name);
      const auto [ma, mb] = materialsOf(*kind, element(spec) + rest, changed + rest);
      EXPECT_NE(ma, mb);
    }
}

TEST(ParameterSet, CanonicalTextNamesEveryField) {
  SpectrumDesc base;
  base.kind = SpectrumDesc::Kind::Pairs;
  base.nm = {400, 700};
  base.value = {0.2, 0.8};
  auto text = [](const SpectrumDesc& s) { return canonicalText(ParamValue(s)); };
  std::set<std::string> seen{text(base)};
  SpectrumDesc s = base;
  s.value[1] = 0.81;
  EXPECT_TRUE(seen.insert(text(s)).second);
  s = base, s.extrapolate = SpectrumDesc::Extrapolation::Hold;
  EXPECT_TRUE(seen.insert(text(s)).second);
  s = base, s.path = "a.csv";
  EXPECT_TRUE(seen.insert(text(s)).second);
  s = base, s.column = "a.csv";
  EXPECT_TRUE(seen.insert(text(s)).second) << "a path and a column of the same text differ";
  s = base, s.texture = "t.exr";
  EXPECT_TRUE(seen.insert(text(s)).second);
  s = base, s.name = "red";
  EXPECT_TRUE(seen.insert(text(s)).second);
  s = base;
  s.loc = {"other.scn", 12};
  EXPECT_FALSE(seen.insert(text(s)).second) << "locations are not part of the value";

  FluorescenceDesc f;
  f.absorptionNm = 450;
  f.stokesNm = 60;
  std::set<std::string> fl{canonicalText(ParamValue(f))};
  for (std::optional<double> FluorescenceDesc::*field :
       {&FluorescenceDesc::widthNm, &FluorescenceDesc::skew, &FluorescenceDesc::quantumYield,
        &FluorescenceDesc::peakAbsorptance}) {
    FluorescenceDesc g = f;
    g.*field = 0.5;
    EXPECT_TRUE(fl.insert(canonicalText(ParamValue(g))).second);
  }

  ParameterSet a, b;
  a.set({"alpha", 0.2, {}});
  a.set({"metal", std::string("gold"), {}});
  b.set({"metal", std::string("gold"), {}});
  b.set({"alpha", 0.2, {}});
  EXPECT_EQ(a.canonicalText(), b.canonicalText());
  b.set({"alpha", 0.25, {}});
  EXPECT_NE(a.canonicalText(), b.canonicalText());
  EXPECT_EQ(b.items().size(), 2u) << "set replaces in place";
}

} // namespace
} // namespace nx
