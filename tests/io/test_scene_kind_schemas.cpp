// The scene reader knows no kind: it reads whatever kinds it is handed (io/scene_kind_schemas.h).
// A made-up set of kinds, unknown to the registries, is read, and its parameters are checked
// at their lines.
#include <gtest/gtest.h>

#include "core/params/scene_limits.h"
#include "io/scene_desc.h"
#include "io/scene_kind_schemas.h"
#include "support/errors.h"

namespace nx {
namespace {

constexpr ParameterRange kSizeRange{0, 10, true, "a size"};

// One shape <blob> with a required <size>, one light kind "glow" with an optional <power>, one
// material "paint" taking nothing, no media.
class ToyKinds final : public SceneKindSchemas {
public:
  std::optional<ShapeKindSchema> shape(std::string_view name) const override {
    static const ShapeParameter p[] = {
        {{"size", ParamType::Number, "scene units", &kSizeRange, "its size", "1"}}};
    if (name != "blob") return std::nullopt;
    return ShapeKindSchema{"blob", false, p,
                           [](const ParameterSet&) { return std::optional<ShapeProblem>(); }};
  }
  std::vector<std::string> shapeNames() const override { return {"blob"}; }
  std::optional<TakenKindSchema> light(std::string_view name) const override {
    static const TakenParameter p[] = {
        {{"power", ParamType::Number, "W", &kSizeRange, "its power", "1"}, "1"}};
    if (name != "glow") return std::nullopt;
    return TakenKindSchema{"glow", p};
  }
  std::optional<TakenKindSchema> medium(std::string_view) const override { return std::nullopt; }
  bool isMaterial(std::string_view name) const override { return name == "paint"; }
  void checkMaterial(std::string_view, const ParameterSet& params) const override {
    if (!params.empty())
      throw Error(params.items().front().loc.str() + ": expected no parameters of paint");
  }
  std::string shapeList() const override { return "blob"; }
  std::string lightList() const override { return "glow"; }
  std::string mediumList() const override { return "(none)"; }
  std::string materialList() const override { return "paint"; }
};

std::string scene(const std::string& body) {
  return "<scene>\n<settings><xres>8</xres><yres>6</yres><mode>spectral_mcpt</mode></settings>\n"
         "<camera><position>0, 0, 0</position><look_at>0, 0, 1</look_at></camera>\n" +
         body + "</scene>\n";
}

TEST(SceneKindSchemas, TheReaderReadsTheKindsItIsHanded) {
  const SceneDesc d = parseScene(scene("<blob><size>2.5</size><material>paint</material></blob>\n"
                                       "<light type=\"glow\"><power>3</power></light>\n"),
                                 "toy.scn", ToyKinds());
  ASSERT_EQ(d.objects.size(), 1u);
  EXPECT_EQ(d.objects[0].shape, "blob");
  EXPECT_EQ(*d.objects[0].geometry.number("size"), 2.5);
  EXPECT_EQ(d.objects[0].geometry.find("size")->loc.str(), "toy.scn:4");
  ASSERT_EQ(d.lights.size(), 1u);
  EXPECT_EQ(d.lights[0].kind, "glow");
  EXPECT_EQ(*d.lights[0].params.number("power"), 3);
}

TEST(SceneKindSchemas, ParametersAndKindsOutsideTheHandedOnesAreRefusedAtTheirLine) {
  const ToyKinds kinds;
  auto errorOf = [&](const std::string& body) {
    return test::errorMessage([&] { parseScene(scene(body), "toy.scn", kinds); });
  };
  // A parameter the kind does not take, at its line, listing what it takes.
  EXPECT_NE(errorOf("<blob><size>1</size>\n<radius>1</radius><material>paint</material></blob>\n")
                .find("toy.scn:5: expected one of <material>"),
            std::string::npos);
  // A value outside the declared range.
  EXPECT_NE(errorOf("<blob><size>11</size><material>paint</material></blob>\n").find("toy.scn:4:"),
            std::string::npos);
  // The registered kinds are not known to a reader handed others.
  EXPECT_NE(errorOf("<sphere><radius>1</radius><material>paint</material></sphere>\n")
                .find("toy.scn:4: expected one of <settings>, <camera>, <light>, <blob>"),
            std::string::npos);
  EXPECT_NE(errorOf("<light type=\"point\"></light>\n").find("expected a light type glow"),
            std::string::npos);
  EXPECT_NE(errorOf("<blob><size>1</size><material>matte</material></blob>\n")
                .find("expected a material paint"),
            std::string::npos);
}

} // namespace
} // namespace nx
