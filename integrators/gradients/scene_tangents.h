#pragma once
// The derivatives of a scene's appearance data with respect to the parameters being
// differentiated (docs/inverse.md): per parameter component ("slot"), what changes in which
// material, emitter or light, as tables the path tracer reads next to the scene's own. Made by
// differencing scenes resolved at nearby parameter values (the resolution is deterministic and
// smooth in every differentiable parameter; linear ones take theirs from the linear map), so every
// parameter of every kind is covered by the same code; the render's derivative itself is estimated
// along the paths (path_gradients.h).

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "integrators/gradients/shape_tangents.h"
#include "integrators/render_scene.h"

namespace nx {

/// d spectrum / d parameter for one slot: a table on the spectrum's own wavelengths, or
/// sampled every 0.25 nm over the traced range.
struct SpectrumTangent {
  uint32_t slot = 0;
  Spectrum d;
};

/// The tangents of one spectrum of the scene, by slot. The derivative with respect to one
/// knot of a table is a hat function over its two neighbours: such slots are kept per table
/// and evaluated sparsely (two knots per wavelength, whatever the table's size), so a render
/// differentiated with respect to every knot of a long table costs little more than one.
class SpectrumTangents {
public:
  /// Adds slot's derivative `d` (a hat function when d is a table with one non-zero value).
  void add(uint32_t slot, Spectrum d);
  /// The entry for tables on `table`'s wavelengths and ends (made when new), for addKnot.
  size_t knotsOf(const TabulatedSpectrum& table);
  /// Adds slot's derivative `value` times the hat of knot j of the tables of entry `table`
  /// (knotsOf's). False, adding nothing, when that knot already has a slot.
  bool addKnot(uint32_t slot, size_t table, size_t j, float value);
  /// True when no slot changes this spectrum.
  bool empty() const { return dense_.empty() && knots_.empty(); }
  /// Calls f(slot, lane, d) for every slot whose derivative d at a lane's wavelength is not 0.
  template <class F>
  void forEach(const SampledWavelengths& lambda, F&& f) const {
    for (const SpectrumTangent& t : dense_) {
      SampledSpectrum d;
      t.d.evaluate(lambda, d);
      for (int i = 0; i < kLanes; ++i)
        if (d[i] != 0) f(t.slot, i, d[i]);
    }
    for (const Knots& k : knots_)
      for (int i = 0; i < kLanes; ++i)
        k.forEach(lambda.lambda[i], [&](uint32_t slot, float d) { f(slot, i, d); });
  }

private:
  /// The slots of one table's knots: slot of knot j (or -1) and its derivative's value there.
  struct Knots {
    std::vector<double> nm;
    bool holdEnds = false;
    std::vector<int64_t> slotOf;
    std::vector<float> valueOf;
    template <class G>
    void forEach(float x, G&& g) const {
      const size_t n = nm.size();
      auto at = [&](size_t j, double w) {
        if (slotOf[j] >= 0 && w != 0)
          g(static_cast<uint32_t>(slotOf[j]), static_cast<float>(w * valueOf[j]));
      };
      if (x < nm.front()) {
        if (holdEnds) at(0, 1);
        return;
      }
      if (x >= nm.back()) {
        if (holdEnds || x == nm.back()) at(n - 1, 1);
        return;
      }
      const size_t j = static_cast<size_t>(
          std::upper_bound(nm.begin(), nm.end(), static_cast<double>(x)) - nm.begin() - 1);
      const double t = (x - nm[j]) / (nm[j + 1] - nm[j]);
      at(j, 1 - t);
      at(j + 1, t);
    }
  };
  std::vector<SpectrumTangent> dense_;
  std::vector<Knots> knots_;
};

/// d M / d parameter of a re-radiation matrix for one slot: the cells, and the elastic part
/// D(o) = scale(o) rho + constant(o) (ReradiationMatrix::elastic).
struct MatrixTangent {
  uint32_t slot = 0;
  std::vector<float> cells; ///< [i * kBins + o], as the matrix's cells
  std::array<float, ReradiationMatrix::kBins> elasticScale{}, elasticConstant{};
};

/// The matrix tangents of one material, by slot. A tangent touching few cells (a measured
/// matrix's cell: its bilinear resampling reaches a few grid cells) is kept per cell, so a
/// vertex looks up the slots of the cell it chose, not every slot's matrix.
class MatrixTangents {
public:
  /// Adds a slot's tangent (sparse when it changes at most kSparseCells cells).
  void add(MatrixTangent t);
  /// Adds a slot's tangent given as its non-zero cells (i * kBins + o, d M[i][o]) and elastic
  /// constants (bin o, d D(o)): what one measured cell's resampling reaches.
  void addSparse(uint32_t slot, std::span<const std::pair<uint32_t, float>> cells,
                 std::span<const std::pair<uint32_t, float>> elasticConstants);
  /// True when no slot changes the matrix.
  bool empty() const { return dense_.empty() && !sparse_; }
  /// Calls f(slot, d M[i][o]) for every slot changing cell (i, o).
  template <class F>
  void forEachCell(int i, int o, F&& f) const {
    const size_t c = static_cast<size_t>(i) * ReradiationMatrix::kBins + static_cast<size_t>(o);
    for (const MatrixTangent& t : dense_)
      if (const float d = t.cells[c]; d != 0) f(t.slot, d);
    if (sparse_)
      for (const CellEntry& e : cells_[c]) f(e.slot, e.d);
  }
  /// Calls f(slot, d scale, d constant) for every slot changing the elastic part of bin o.
  template <class F>
  void forEachElastic(int o, F&& f) const {
    const size_t b = static_cast<size_t>(o);
    for (const MatrixTangent& t : dense_)
      if (t.elasticScale[b] != 0 || t.elasticConstant[b] != 0)
        f(t.slot, t.elasticScale[b], t.elasticConstant[b]);
    if (sparse_)
      for (const ElasticEntry& e : elastic_[b]) f(e.slot, e.scale, e.constant);
  }
  /// Most cells a sparse tangent may change.
  static constexpr size_t kSparseCells = 512;

private:
  struct CellEntry {
    uint32_t slot;
    float d;
  };
  struct ElasticEntry {
    uint32_t slot;
    float scale, constant;
  };
  std::vector<MatrixTangent> dense_;
  bool sparse_ = false;
  std::vector<std::vector<CellEntry>> cells_;      ///< [i * kBins + o], once a sparse one came
  std::vector<std::vector<ElasticEntry>> elastic_; ///< [o]
};

/// d alpha_u / d parameter and d alpha_v / d parameter of a rough conductor for one slot.
struct RoughnessTangent {
  uint32_t slot = 0;
  float alphaU = 0, alphaV = 0;
};

/// d / d parameter of a homogeneous medium for one slot: its coefficients, its phase function's
/// g, and its dye (peak and matrix: absorptance a, column sums c, cells M per peak 1).
struct MediumTangent {
  uint32_t slot = 0;
  Spectrum sigmaA, sigmaS; ///< d sigma_a, d sigma_s
  float g = 0, dyePeak = 0;
  std::vector<float> dyeCells; ///< [i * kBins + o]; empty without a dye
  std::array<float, ReradiationMatrix::kBins> dyeAbsorptance{}, dyeColumnSum{};
};

/// Every slot's derivatives, indexed like the scene's tables.
struct SceneTangents {
  std::vector<std::string> slotNames; ///< what each slot is, e.g. "objects[1].reflectance[3]"
  std::vector<SpectrumTangents> reflectance; ///< per RenderScene::materials
  /// Per material: the first of its image texture's valueCount() slots (value q: slot
  /// first + q), or -1 when its texels are not differentiated.
  std::vector<int64_t> textureFirstSlot;
  /// Per material: the first of its concentration map's values' slots, or -1.
  std::vector<int64_t> concentrationFirstSlot;
  std::vector<MatrixTangents> reradiation;              ///< per RenderScene::materials
  std::vector<std::vector<RoughnessTangent>> roughness; ///< per RenderScene::materials
  std::vector<SpectrumTangents> emission;               ///< per RenderScene::emission
  std::vector<SpectrumTangents> lights;                 ///< per RenderScene::lights (intensity)
  SpectrumTangents background;
  std::vector<std::vector<MediumTangent>> media; ///< per RenderScene::media
  ShapeTangents shapes; ///< how slots move the geometry (shape and camera parameters)
  /// Slots whose parameter changes nothing the scene renders (their derivative is 0).
  std::vector<uint32_t> inert;

  /// Number of slots.
  uint32_t slots() const { return static_cast<uint32_t>(slotNames.size()); }
  /// Tables sized for `scene`, no slot yet.
  static SceneTangents sizedFor(const RenderScene& scene);
};

/// Adds slot `name`: the derivative of `base`'s appearance data as sum_i weights[i] * scenes[i]
/// (a finite-difference stencil over scenes resolved at nearby values of one parameter, e.g.
/// (+1/2h, -1/2h)). Throws nx::Error naming `name` when the scenes differ in what is not
/// differentiated (structure, geometry, roughness, indices of refraction, textures, environment
/// maps, a medium's emission or an emitting medium's absorption) or when fluorescence appears or
/// vanishes. Returns the new slot.
uint32_t addTangentSlot(SceneTangents& tangents, const std::string& name, const RenderScene& base,
                        std::span<const RenderScene* const> scenes,
                        std::span<const double> weights);

/// Adds one slot per value of the image textures that differ between `base` and `changed` (a
/// scene resolved with the parameter's texture altered), named name[q] (q: texel * bands + band,
/// texels row by row from the top). Throws nx::Error naming `name` when anything else differs,
/// when no texture or a texture of another kind or size changed. Returns the first slot.
uint32_t addTextureSlots(SceneTangents& tangents, const std::string& name, const RenderScene& base,
                         const RenderScene& changed);

/// Adds one slot per cell of a measured matrix whose cells are `cells` and resampling `map`
/// (fromMeasured's), named name[q] (q: row * columns + column), each cell's tangent taken from
/// the map (the resampling is linear in the cells: no resolved copies per cell). `changed` is
/// the scene resolved with every cell moved: the materials it differs in are the matrix's.
/// Returns the first slot, or nullopt (no slot added) when the map does not reproduce those
/// materials' matrices or more than their matrices changed (then differentiate per cell).
std::optional<uint32_t> addMeasuredCellSlots(SceneTangents& tangents, const std::string& name,
                                             const RenderScene& base, const RenderScene& changed,
                                             const MeasuredResampling& map,
                                             std::span<const double> cells);

/// Adds one slot per knot of a table whose values are `values`, where the scene renders the
/// table itself: every spectrum that `changed` (the scene resolved with the knots at `moved`)
/// differs in (a reflectance, an emission, a light's or the background's spectrum) is, in both
/// scenes, a table on the knots' wavelengths whose values are one constant c times the knots'.
/// Knot j's tangent is then c times its hat (the table is linear in its knots: no resolved
/// copies per knot). Named name[j]. Returns the first slot, or nullopt (no slot added) where
/// anything else changed (a dye built from the table, a normalised spectrum, a medium's
/// coefficients): then differentiate per knot.
std::optional<uint32_t> addTableKnotSlots(SceneTangents& tangents, const std::string& name,
                                          const RenderScene& base, const RenderScene& changed,
                                          std::span<const double> values,
                                          std::span<const double> moved);

/// Adds one slot per value of the concentration map that differs between `base` and `changed`
/// (a scene resolved with the map altered), named name[q] (q: row * width + column). Throws
/// nx::Error naming `name` when anything else differs or no map changed. Returns the first slot.
uint32_t addConcentrationSlots(SceneTangents& tangents, const std::string& name,
                               const RenderScene& base, const RenderScene& changed);

} // namespace nx
