// Scenes as data: a scene written back as text (Scene.to_text) or as a tree (Scene.to_dict)
// reads back to the same scene state, for every example scene and every scene of the
// malformed-scene corpus that reads (its problems are found later, at the build); a tree's
// errors name its path.

#include <gtest/gtest.h>

#include <filesystem>

#include "core/error.h"
#include "integrators/scene_reader.h"
#include "io/scene_desc.h"
#include "io/scene_state_text.h"
#include "io/scene_to_tree.h"
#include "io/scene_tree_text.h"
#include "support/errors.h"

namespace nx {
namespace {

namespace fs = std::filesystem;

// The state without what only a calibration file's name adds (its values are written out).
std::string stateOf(SceneDesc d) {
  d.camera.calibrationFile.clear();
  d.camera.calibrationDigest = 0;
  d.camera.calibrationSize.reset();
  return sceneStateText(d);
}

// Every scene file under scenes/ and tests/ that reads without error.
std::vector<fs::path> readableScenes() {
  std::vector<fs::path> out;
  for (const char* dir : {"scenes", "tests"})
    for (const auto& e : fs::recursive_directory_iterator(fs::path(NX_SOURCE_DIR) / dir))
      if (e.path().extension() == ".scn") try {
          loadScene(e.path().string());
          out.push_back(e.path());
        } catch (const Error&) {
        }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(SceneText, EveryReadableSceneRoundTripsThroughTextAndTree) {
  const auto scenes = readableScenes();
  EXPECT_GE(scenes.size(), 40u); // the examples and the corpus's scenes that read
  for (const fs::path& p : scenes) {
    SCOPED_TRACE(p.string());
    const SceneDesc d = loadScene(p.string());
    // Text read back where the file is: file names relative to its directory.
    const std::string text = sceneToText(d, p.parent_path().string());
    const SceneDesc fromText = parseScene(text, p.string());
    EXPECT_EQ(stateOf(fromText), stateOf(d)) << text;
    // The tree, read as Scene.from_dict reads it (file names as the scene holds them).
    const SceneDesc fromTree = parseSceneTree(sceneToTree(d), "<dict>");
    EXPECT_EQ(stateOf(fromTree), stateOf(d));
    // and writing it again gives the same text (nothing is lost or reordered twice)
    EXPECT_EQ(sceneToText(fromText, p.parent_path().string()), text);
  }
}

// A sphere in a scene, and `object` after it unless it is empty.
SceneTree minimalScene(SceneTree::Dict object) {
  using D = SceneTree::Dict;
  using L = SceneTree::List;
  SceneTree t =
      D{{"settings", D{{"xres", 8.0}, {"yres", 6.0}, {"mode", std::string("spectral_mcpt")}}},
        {"camera", D{{"position", L{0.0, 0.0, -5.0}}, {"look_at", L{0.0, 0.0, 0.0}}}},
        {"objects", L{D{{"shape", std::string("sphere")},
                        {"center", L{0.0, 0.0, 0.0}},
                        {"radius", 1.0},
                        {"material", std::string("matte")},
                        {"reflectance", 0.5}}}}};
  if (!object.empty())
    std::get<L>(std::get<D>(t.value).back().second.value).emplace_back(std::move(object));
  return t;
}

TEST(SceneText, TreeErrorsNameThePathInTheTree) {
  using D = SceneTree::Dict;
  using L = SceneTree::List;
  const std::string sphere = "sphere";
  auto error = [](const SceneTree& t) {
    return test::errorMessage([&] { parseSceneTree(t, "<dict>"); });
  };
  EXPECT_EQ(error(minimalScene(D{{"shape", sphere},
                                 {"center", L{0.0, 0.0, 0.0}},
                                 {"radius", -1.0},
                                 {"material", std::string("matte")}})),
            "objects[1].radius: expected a radius in (0, 1e+12], found '-1'");
  EXPECT_EQ(error(minimalScene(D{{"center", L{0.0, 0.0, 0.0}}})),
            "objects[1]: expected a \"shape\" (sphere, plane, mesh, ...), found none");
  EXPECT_EQ(error(minimalScene(D{{"shape", sphere},
                                 {"center", L{0.0, 0.0}},
                                 {"radius", 1.0},
                                 {"material", std::string("matte")}})),
            "objects[1].center: expected 3 numbers (a sphere centre x, y, z) in <center>, found 2 "
            "('0, 0')");
  SceneTree noSettings = minimalScene(D{});
  std::get<D>(noSettings.value).erase(std::get<D>(noSettings.value).begin());
  EXPECT_EQ(error(noSettings), "scene: expected a <settings> element, found none");
  SceneTree extra = minimalScene(D{});
  std::get<D>(extra.value).emplace_back("object", D{});
  EXPECT_EQ(error(extra), "object: expected one of the sections settings, camera, objects, "
                          "lights, materials, spectra, found 'object'");
}

TEST(SceneText, MeshRowsRoundTripExactly) {
  using D = SceneTree::Dict;
  SceneTree::Array v{
      {0.1, 0, 0, 1.0 / 3, 0, 0, 0, 1e-7, 2.5}, 3, 3, SceneTree::Array::Kind::Float32};
  SceneTree::Array f{{0, 1, 2}, 1, 3, SceneTree::Array::Kind::Integer};
  const SceneDesc d = parseSceneTree(minimalScene(D{{"shape", std::string("mesh")},
                                                    {"vertices", v},
                                                    {"faces", f},
                                                    {"material", std::string("matte")}}),
                                     "<dict>");
  const ArrayDesc& rows = *d.objects[1].geometry.get<ArrayDesc>("vertices");
  ASSERT_EQ(rows.rows(), 3u);
  for (size_t i = 0; i < v.values.size(); ++i)
    EXPECT_EQ((*rows.reals)[i], static_cast<float>(v.values[i])); // one rounding, to float
  EXPECT_EQ(stateOf(parseScene(sceneToText(d), "t.scn")), stateOf(d));
}

} // namespace
} // namespace nx
