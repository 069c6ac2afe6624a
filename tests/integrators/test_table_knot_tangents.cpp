// A table's knots differentiated through the table itself (addTableKnotSlots: each knot's
// tangent is its hat) against per-knot differences of resolved scenes (the route every other
// parameter takes): a reflectance, an area lamp's and a point light's spectrum, the
// background; and a dye's datasheet spectra, which the table does not reach linearly (the
// emission is normalised), so the set-up must fall back to differences there.

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <utility>

#include "integrators/gradients/gradient_setup.h"
#include "integrators/render_scene.h"
#include "integrators/scene_params/parameter_numbers.h"
#include "integrators/scene_reader.h"

namespace nx {
namespace {

const char* kScene =
    "<scene><settings><xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode><depth>3</depth>"
    "<sampl>1</sampl><bands>400:700:50</bands><background>400:0.01, 550:0.02, 700:0.03"
    "</background></settings><camera><position>0,1,-5</position><look_at>0,0.5,0</look_at>"
    "<fov>40</fov></camera><plane><normal>0,1,0</normal><distance>0</distance><material>matte"
    "</material><reflectance>400:0.2, 500:0.5, 600:0.4, 700:0.8</reflectance></plane><sphere>"
    "<center>0,0.7,0</center><radius>0.7</radius><material>matte</material><reflectance>0.3"
    "</reflectance><fluorescence><absorptance>400:0.1, 450:0.8, 500:0.3, 550:0</absorptance>"
    "<emission>450:0, 500:1, 550:3, 650:0.5, 700:0</emission><yield>0.7</yield></fluorescence>"
    "</sphere><sphere><center>2,2,0</center><radius>0.3</radius><material>matte</material>"
    "<reflectance>0</reflectance><emission scale=\"0.01\">380:1, 480:2, 520:0.1, 800:0.1"
    "</emission></sphere><light><position>0,3,-2</position><color>1,1,1</color><emission "
    "scale=\"0.02\">380:1, 500:3, 800:2</emission></light></scene>";

using Values = std::map<std::pair<uint32_t, int>, double>;

// (slot, where) -> derivative for every spectrum and matrix of t: spectra sampled every 1.75 nm
// over 380-800 nm (where: which spectrum * 1000 + sample), matrices cell by cell.
Values values(const SceneTangents& t) {
  Values out;
  int which = 0;
  auto spectrum = [&](const SpectrumTangents& s) {
    for (int g = 0; g < 240; g += kLanes) {
      SampledWavelengths l;
      for (int i = 0; i < kLanes; ++i)
        l.lambda[static_cast<size_t>(i)] = static_cast<float>(380 + 1.75 * (g + i));
      s.forEach(l, [&](uint32_t slot, int lane, float d) {
        out[{slot, which * 1000 + g + lane}] += d;
      });
    }
    ++which;
  };
  for (const auto& s : t.reflectance) spectrum(s);
  for (const auto& s : t.emission) spectrum(s);
  for (const auto& s : t.lights) spectrum(s);
  spectrum(t.background);
  constexpr int n = ReradiationMatrix::kBins;
  for (const auto& m : t.reradiation) {
    for (int i = 0; i < n; ++i)
      for (int o = i + 1; o < n; ++o)
        m.forEachCell(i, o, [&](uint32_t slot, float d) {
          out[{slot, 100000 + which * n * n + i * n + o}] += d;
        });
    ++which;
  }
  return out;
}

// gradientSetup's tangents of `name` against central differences of resolved scenes per knot,
// to `tolerance` of the largest derivative.
void expectKnotsMatchDifferences(const std::string& name, double tolerance) {
  const SceneDesc desc = parseScene(kScene, "t.scn");
  const RenderScene base = resolveRenderScene(desc);
  const GradientSetup setup = gradientSetup(desc, {name}, base, true);
  const ParameterNumbers n = parameterNumbers(desc, name);
  ASSERT_EQ(n.form, ParameterNumbers::Form::Table);
  ASSERT_EQ(setup.tangents.slots(), n.values.size());
  SceneTangents fd = SceneTangents::sizedFor(base);
  for (size_t j = 0; j < n.values.size(); ++j) {
    const double h = 1e-4;
    auto with = [&](double d) {
      SceneDesc copy = desc;
      std::vector<double> v = n.values;
      v[j] += d;
      EXPECT_TRUE(setParameterNumbers(copy, name, v));
      return resolveRenderScene(copy);
    };
    // Central, or forward at a knot at 0 (a spectrum is not negative).
    const bool central = n.values[j] >= h;
    const RenderScene plus = with(h), minus = central ? with(-h) : base;
    const RenderScene* scenes[] = {&plus, &minus};
    const double w[] = {(central ? 0.5 : 1) / h, -(central ? 0.5 : 1) / h};
    addTangentSlot(fd, name, base, scenes, w);
  }
  const Values fromSetup = values(setup.tangents), fromDifferences = values(fd);
  double largest = 0;
  for (const auto& [key, d] : fromDifferences) largest = std::max(largest, std::abs(d));
  ASSERT_GT(largest, 0.0);
  size_t compared = 0;
  for (const auto& [key, d] : fromDifferences) {
    if (std::abs(d) <= 1e-6 * largest) continue;
    const auto it = fromSetup.find(key);
    ASSERT_NE(it, fromSetup.end()) << "slot " << key.first << " at " << key.second;
    EXPECT_NEAR(it->second, d, tolerance * largest) << "slot " << key.first << " at " << key.second;
    ++compared;
  }
  for (const auto& [key, d] : fromSetup) {
    if (std::abs(d) > tolerance * largest) {
      EXPECT_TRUE(fromDifferences.count(key)) << "slot " << key.first << " at " << key.second;
    }
  }
  EXPECT_GT(compared, n.values.size());
}

TEST(TableKnotTangents, ReflectanceKnotsAreTheirHats) {
  expectKnotsMatchDifferences("objects[0].reflectance", 1e-5);
}

TEST(TableKnotTangents, EmittersAndBackgroundKnotsAreTheirHats) {
  // Scaled tables: the hat carries the scale.
  expectKnotsMatchDifferences("objects[2].emission", 1e-5);
  expectKnotsMatchDifferences("lights[0].emission", 1e-5);
  expectKnotsMatchDifferences("background", 1e-5);
}

TEST(TableKnotTangents, DyeDatasheetSpectraFallBackToDifferences) {
  // The emission spectrum is normalised and the matrix is a product: not the table itself.
  expectKnotsMatchDifferences("objects[1].fluorescence.absorptance", 2e-3);
  expectKnotsMatchDifferences("objects[1].fluorescence.emission", 2e-3);
}

} // namespace
} // namespace nx
