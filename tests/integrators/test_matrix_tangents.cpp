// A measured matrix's cells differentiated through fromMeasured's resampling map
// (addMeasuredCellSlots): every cell's tangent against the difference of scenes resolved at a
// nearby value of that cell (the route every other parameter takes), for a matrix
// with a diagonal and for one without.

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <utility>

#include "integrators/gradients/gradient_setup.h"
#include "integrators/render_scene.h"
#include "integrators/scene_params/scene_fields.h"
#include "integrators/scene_reader.h"

namespace nx {
namespace {

const char* kScene =
    "<scene><settings><xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode><depth>3</depth>"
    "<sampl>1</sampl><bands>400:700:50</bands></settings><camera><position>0,1,-5</position>"
    "<look_at>0,0.5,0</look_at><fov>40</fov></camera><plane><normal>0,1,0</normal><distance>0"
    "</distance><material>matte</material><reflectance>0.5</reflectance></plane><sphere><center>"
    "0,0.7,0</center><radius>0.7</radius><material>matte</material><reflectance>0.3</reflectance>"
    "<fluorescence><absorption>460</absorption><stokes>90</stokes><width>25</width><yield>0.8"
    "</yield></fluorescence></sphere><light><position>0,3,-2</position><color>1,1,1</color>"
    "<emission scale=\"0.02\">D65</emission></light></scene>";
const std::string kName = "objects[1].fluorescence.matrix";

// A matrix on excitation ex and emission em: a Stokes-shifted band, and `diagonal` on the
// cells where the two wavelengths coincide.
std::shared_ptr<const MeasuredMatrix> matrix(std::vector<double> ex, std::vector<double> em,
                                             double diagonal) {
  auto m = std::make_shared<MeasuredMatrix>();
  m->excitationNm = std::move(ex);
  m->emissionNm = std::move(em);
  for (double x : m->excitationNm)
    for (double e : m->emissionNm)
      m->cells.push_back(std::abs(x - e) < 1e-9 ? diagonal
                         : e > x                ? 0.02 * std::exp(-std::pow((e - x - 70) / 40, 2))
                                                : 0.0);
  m->source = "the test's matrix";
  return m;
}

// Every (slot, cell or elastic bin) -> derivative of material m's matrix in t.
std::map<std::pair<uint32_t, int>, double> entries(const SceneTangents& t, size_t m) {
  constexpr int n = ReradiationMatrix::kBins;
  std::map<std::pair<uint32_t, int>, double> out;
  for (int i = 0; i < n; ++i)
    for (int o = i + 1; o < n; ++o)
      t.reradiation[m].forEachCell(i, o, [&](uint32_t slot, float d) {
        out[{slot, i * n + o}] += d;
      });
  for (int o = 0; o < n; ++o)
    t.reradiation[m].forEachElastic(o, [&](uint32_t slot, float scale, float constant) {
      EXPECT_EQ(scale, 0.0f);
      out[{slot, n * n + o}] += constant;
    });
  return out;
}

// The map's tangents (what gradientSetup gives) against per-cell differences of resolved
// scenes (addTangentSlot), every cell.
void expectMapMatchesDifferences(const std::shared_ptr<const MeasuredMatrix>& mm) {
  SceneDesc desc = parseScene(kScene, "t.scn");
  setSceneField(desc, kName, mm);
  const RenderScene base = resolveRenderScene(desc);
  const GradientSetup setup = gradientSetup(desc, {kName}, base, true);
  ASSERT_EQ(setup.tangents.slots(), mm->cells.size());
  size_t material = base.materials.size();
  for (size_t m = 0; m < base.materials.size(); ++m)
    if (base.materials[m].reradiation) material = m;
  ASSERT_LT(material, base.materials.size());
  const auto fromMap = entries(setup.tangents, material);
  SceneTangents fd = SceneTangents::sizedFor(base);
  size_t reached = 0;
  for (size_t q = 0; q < mm->cells.size(); ++q) {
    const double h = 1e-3;
    auto with = [&](double d) {
      auto changed = std::make_shared<MeasuredMatrix>(*mm);
      changed->cells[q] += d;
      SceneDesc copy = desc;
      setSceneField(copy, kName, std::shared_ptr<const MeasuredMatrix>(changed));
      return resolveRenderScene(copy);
    };
    // The resampling is linear: a forward difference is exact (and a cell at 0 cannot go down).
    const RenderScene plus = with(h);
    const RenderScene* scenes[] = {&plus, &base};
    const double w[] = {1 / h, -1 / h};
    addTangentSlot(fd, "cell", base, scenes, w);
    const bool inert = std::find(setup.tangents.inert.begin(), setup.tangents.inert.end(), q) !=
                       setup.tangents.inert.end();
    EXPECT_EQ(inert, std::find(fd.inert.begin(), fd.inert.end(), q) != fd.inert.end())
        << "cell " << q;
    reached += !inert;
  }
  EXPECT_GT(reached, mm->cells.size() / 4);
  const auto fromDifferences = entries(fd, material);
  EXPECT_EQ(fromMap.size(), fromDifferences.size());
  for (const auto& [key, d] : fromDifferences) {
    const auto it = fromMap.find(key);
    ASSERT_NE(it, fromMap.end()) << "slot " << key.first << " cell " << key.second;
    EXPECT_NEAR(it->second, d, 1e-5 * std::abs(d) + 1e-7)
        << "slot " << key.first << " cell " << key.second;
  }
}

TEST(MatrixTangents, ResamplingMapMatchesDifferencesWithADiagonal) {
  // Excitation and emission share 400-520 nm: a diagonal (the elastic part) and cells on both
  // sides of it.
  expectMapMatchesDifferences(
      matrix({380, 400, 430, 460, 490, 520}, {400, 430, 460, 490, 520, 550, 580, 610, 640}, 0.3));
}

TEST(MatrixTangents, ResamplingMapMatchesDifferencesWithoutADiagonal) {
  // No wavelength in common: the elastic part is the reflectance, not the cells'.
  expectMapMatchesDifferences(
      matrix({351, 377, 403, 429, 455, 481}, {412, 437, 463, 489, 515, 541, 567, 593, 619}, 0));
}

TEST(MatrixTangents, ResampledMatrixIsTheMapApplied) {
  // fromMeasured is its map applied to the cells: a cell's matrix is the map's weights.
  const auto mm = matrix({400, 430, 460}, {400, 430, 460, 490, 520}, 0.2);
  const ReradiationMatrix r = ReradiationMatrix::fromMeasured(*mm);
  const MeasuredResampling map = measuredResampling(*mm);
  constexpr int n = ReradiationMatrix::kBins;
  std::vector<double> applied(static_cast<size_t>(n) * n + n, 0.0);
  for (const auto& t : map.terms) applied[t.output] += t.w * mm->cells[t.input];
  double largest = 0;
  for (int i = 0; i < n; ++i)
    for (int o = i + 1; o < n; ++o) {
      EXPECT_DOUBLE_EQ(r(i, o), applied[static_cast<size_t>(i) * n + o]);
      largest = std::max(largest, r(i, o));
    }
  EXPECT_GT(largest, 0.0);
  // A bin's diagonal between the measured 430 and 460 nm: linear between them.
  const int bin = ReradiationMatrix::binOf(445);
  EXPECT_NEAR(r.elastic(bin, 0.0), 0.2, 1e-12);
  EXPECT_DOUBLE_EQ(r.elastic(bin, 0.0), applied[MeasuredResampling::diagonal(bin)]);
}

} // namespace
} // namespace nx
