#include "integrators/gradients/scene_tangents.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "integrators/gradients/light_gradients.h"
#include "integrators/materials/bsdf.h"

namespace nx {
namespace {

constexpr int kGridPoints =
    static_cast<int>((kTraceMaxNm - kTraceMinNm) / DenseSpectrum::stepNm) + 1;

double gridNm(int i) {
  return kTraceMinNm + i * DenseSpectrum::stepNm;
}

// sum_i w_i s_i(nm) on the tangents' grid; `changed` when some value differs from 0 by more
// than rounding (relative to the spectra's size).
DenseSpectrum stencil(std::span<const Spectrum* const> spectra, std::span<const double> w,
                      bool& changed) {
  DenseSpectrum out;
  out.value.resize(kGridPoints);
  changed = false;
  for (int g = 0; g < kGridPoints; ++g) {
    const double nm = gridNm(g);
    double sum = 0, size = 0;
    for (size_t i = 0; i < spectra.size(); ++i) {
      const double v = (*spectra[i])(nm);
      sum += w[i] * v;
      size = std::max(size, std::abs(w[i] * v));
    }
    if (std::abs(sum) > 1e-9 * size && sum != 0) changed = true;
    out.value[static_cast<size_t>(g)] = static_cast<float>(sum);
  }
  return out;
}

// True when the spectra agree everywhere on the grid (to rounding).
bool sameSpectrum(const Spectrum& a, const Spectrum& b) {
  for (int g = 0; g < kGridPoints; g += 4) {
    const double x = a(gridNm(g)), y = b(gridNm(g));
    if (std::abs(x - y) > 1e-12 * std::max(std::abs(x), std::abs(y))) return false;
  }
  return true;
}

[[noreturn]] void notDifferentiated(const std::string& name, const std::string& what) {
  throw Error(name + ": not differentiable: it changes " + what +
              " (docs/inverse.md lists what is differentiated)");
}

// What of material m besides its reflectance and matrix differs between a and b, or "".
// Whether two materials' concentration maps differ.
bool concentrationDiffers(const Material& a, const Material& b) {
  if ((a.concentration == nullptr) != (b.concentration == nullptr)) return true;
  return a.concentration && a.concentration->digest != b.concentration->digest;
}

std::string otherMaterialChange(const Material& a, const Material& b, bool texture = false,
                                bool concentration = false) {
  if (!concentration && concentrationDiffers(a, b)) return "a concentration map";
  if (a.kind != b.kind) return "the material's kind";
  if (a.roughness != b.roughness) return "the mixture's roughness";
  // The model says whether its roughness is differentiated (a rough conductor's: yes; not at
  // 0, where a smooth metal's lobe is a delta; a rough dielectric's: no).
  if ((a.alphaU != b.alphaU || a.alphaV != b.alphaV) && !roughnessDifferentiable(a)) {
    const uint8_t lobes = materialLobes(a);
    if (lobes & (kGlossyTransmission | kSpecularTransmission))
      return "the microfacet roughness of a dielectric (not differentiated)";
    return lobes & kGlossyReflection
               ? "the microfacet roughness of this kind (not differentiated)"
               : "the microfacet roughness of a smooth metal (its lobe is a delta: differentiate "
                 "from alpha > 0)";
  }
  if (a.modelConstants != b.modelConstants)
    return "a constant of the scattering model (rough_matte's <sigma>; not differentiated)";
  if (a.coatInternalReflectance != b.coatInternalReflectance) return "the coat";
  if (a.coatingNm != b.coatingNm) return "the thin-film coating";
  for (double nm = kTraceMinNm; nm <= kTraceMaxNm; nm += 10) {
    if (a.ior.at(nm) != b.ior.at(nm) || a.coatingIor.at(nm) != b.coatingIor.at(nm))
      return "an index of refraction";
  }
  if (!sameSpectrum(a.conductorEta, b.conductorEta) || !sameSpectrum(a.conductorK, b.conductorK))
    return "a conductor's complex index";
  if ((a.texture == nullptr) != (b.texture == nullptr)) return "whether a texture is used";
  if (!texture && a.texture && !a.texture->sameAs(*b.texture)) return "a texture's texels";
  if ((a.reradiation == nullptr) != (b.reradiation == nullptr))
    return "whether the surface fluoresces";
  return "";
}

// What of a medium that is not differentiated differs between a and b, or "".
std::string otherMediumChange(const HomogeneousMedium& a, const HomogeneousMedium& b) {
  if ((a.dye == nullptr) != (b.dye == nullptr)) return "whether a medium holds a dye";
  if (a.emission.has_value() != b.emission.has_value() ||
      (a.emission && !sameSpectrum(*a.emission, *b.emission)))
    return "a medium's emission";
  if (a.emission && (!sameSpectrum(a.sigmaA, b.sigmaA) || !sameSpectrum(a.sigmaS, b.sigmaS) ||
                     a.g != b.g || a.dyePeak != b.dyePeak))
    return "an emitting medium (its glow along a flight is not differentiated)";
  return "";
}

// The stencil over one spectrum of every scene; appended to `out` as slot's tangent when it
// changes.
template <class Get>
bool addSpectrumTangent(SpectrumTangents& out, uint32_t slot,
                        std::span<const RenderScene* const> scenes, std::span<const double> w,
                        Get&& get) {
  std::vector<const Spectrum*> spectra;
  for (const RenderScene* s : scenes) spectra.push_back(&get(*s));
  bool changed = false;
  DenseSpectrum d = stencil(spectra, w, changed);
  if (!changed) return false;
  // Tables on the same wavelengths: the stencil of their values, exact (a table's end stays
  // where it is; the dense grid would smear it over 0.25 nm).
  const auto* first = std::get_if<TabulatedSpectrum>(&spectra[0]->kind());
  bool sameTables = first != nullptr;
  for (const Spectrum* sp : spectra) {
    const auto* t = std::get_if<TabulatedSpectrum>(&sp->kind());
    sameTables = sameTables && t && t->nm == first->nm && t->holdEnds == first->holdEnds;
  }
  if (sameTables) {
    TabulatedSpectrum table = *first;
    for (size_t k = 0; k < table.value.size(); ++k) {
      double sum = 0;
      for (size_t i = 0; i < spectra.size(); ++i)
        sum +=
            w[i] * spectra[i]->scale() * std::get<TabulatedSpectrum>(spectra[i]->kind()).value[k];
      table.value[k] = sum;
    }
    out.add(slot, Spectrum(std::move(table)));
  } else {
    out.add(slot, Spectrum(std::move(d)));
  }
  return true;
}

} // namespace

void SpectrumTangents::add(uint32_t slot, Spectrum d) {
  if (const auto* t = std::get_if<TabulatedSpectrum>(&d.kind())) {
    size_t nonZero = 0, at = 0;
    for (size_t j = 0; j < t->value.size(); ++j)
      if (t->value[j] != 0) ++nonZero, at = j;
    if (nonZero == 1 &&
        addKnot(slot, knotsOf(*t), at, static_cast<float>(d.scale() * t->value[at])))
      return;
  }
  dense_.push_back({slot, std::move(d)});
}

size_t SpectrumTangents::knotsOf(const TabulatedSpectrum& table) {
  for (size_t e = 0; e < knots_.size(); ++e)
    if (knots_[e].nm == table.nm && knots_[e].holdEnds == table.holdEnds) return e;
  knots_.push_back({table.nm, table.holdEnds, std::vector<int64_t>(table.nm.size(), -1),
                    std::vector<float>(table.nm.size(), 0.0f)});
  return knots_.size() - 1;
}

bool SpectrumTangents::addKnot(uint32_t slot, size_t table, size_t j, float value) {
  Knots& k = knots_[table];
  if (k.slotOf[j] >= 0) return false;
  k.slotOf[j] = slot;
  k.valueOf[j] = value;
  return true;
}

void MatrixTangents::add(MatrixTangent t) {
  constexpr int n = ReradiationMatrix::kBins;
  size_t changed = 0;
  for (float d : t.cells) changed += d != 0;
  for (int o = 0; o < n; ++o)
    changed += t.elasticScale[static_cast<size_t>(o)] != 0 ||
               t.elasticConstant[static_cast<size_t>(o)] != 0;
  if (changed > kSparseCells) {
    dense_.push_back(std::move(t));
    return;
  }
  if (!sparse_) {
    cells_.resize(static_cast<size_t>(n) * n);
    elastic_.resize(static_cast<size_t>(n));
    sparse_ = true;
  }
  for (size_t c = 0; c < t.cells.size(); ++c)
    if (t.cells[c] != 0) cells_[c].push_back({t.slot, t.cells[c]});
  for (size_t o = 0; o < static_cast<size_t>(n); ++o)
    if (t.elasticScale[o] != 0 || t.elasticConstant[o] != 0)
      elastic_[o].push_back({t.slot, t.elasticScale[o], t.elasticConstant[o]});
}

void MatrixTangents::addSparse(uint32_t slot, std::span<const std::pair<uint32_t, float>> cells,
                               std::span<const std::pair<uint32_t, float>> elasticConstants) {
  constexpr int n = ReradiationMatrix::kBins;
  if (!sparse_) {
    cells_.resize(static_cast<size_t>(n) * n);
    elastic_.resize(static_cast<size_t>(n));
    sparse_ = true;
  }
  for (const auto& [c, d] : cells)
    if (d != 0) cells_[c].push_back({slot, d});
  for (const auto& [o, d] : elasticConstants)
    if (d != 0) elastic_[o].push_back({slot, 0.0f, d});
}

SceneTangents SceneTangents::sizedFor(const RenderScene& scene) {
  SceneTangents t;
  t.reflectance.resize(scene.materials.size());
  t.reradiation.resize(scene.materials.size());
  t.roughness.resize(scene.materials.size());
  t.emission.resize(scene.emission.size());
  t.lights.resize(scene.lights.size());
  t.media.resize(scene.media.size());
  t.textureFirstSlot.assign(scene.materials.size(), -1);
  t.concentrationFirstSlot.assign(scene.materials.size(), -1);
  if (scene.geometry) {
    forEachAnalyticKind(
        [&]<class P>() { t.shapes.motions<P>().resize(scene.geometry->primitives<P>().size()); });
    t.shapes.meshes.resize(scene.geometry->meshes().size());
  }
  return t;
}

uint32_t addTangentSlot(SceneTangents& t, const std::string& name, const RenderScene& base,
                        std::span<const RenderScene* const> scenes,
                        std::span<const double> weights) {
  const uint32_t slot = t.slots();
  bool any = false;
  for (const RenderScene* s : scenes) {
    if (s->materials.size() != base.materials.size() ||
        s->emission.size() != base.emission.size() || s->lights.size() != base.lights.size() ||
        s->media.size() != base.media.size() ||
        s->background.has_value() != base.background.has_value())
      notDifferentiated(name, "the scene's structure (what emits, what is a light or a medium)");
    if (s->settings.width != base.settings.width || s->settings.height != base.settings.height ||
        s->settings.depth != base.settings.depth)
      notDifferentiated(name, "the scene's settings");
    for (size_t m = 0; m < base.materials.size(); ++m) {
      const std::string other = otherMaterialChange(base.materials[m], s->materials[m]);
      if (!other.empty()) notDifferentiated(name, other);
    }
    for (size_t k = 0; k < base.media.size(); ++k) {
      const std::string other = otherMediumChange(base.media[k], s->media[k]);
      if (!other.empty()) notDifferentiated(name, other);
    }
    for (size_t l = 0; l < base.lights.size(); ++l) {
      if (!sameLightPlacement(base.lights[l], s->lights[l]))
        notDifferentiated(name, "where a light is or how it is aimed");
      if (const std::string other = otherLightChange(base.lights[l], s->lights[l]); !other.empty())
        notDifferentiated(name, other);
    }
  }
  for (size_t m = 0; m < base.materials.size(); ++m) {
    const bool changed = addSpectrumTangent(
        t.reflectance[m], slot, scenes, weights,
        [m](const RenderScene& s) -> const Spectrum& { return s.materials[m].reflectance; });
    if (changed && base.materials[m].texture)
      notDifferentiated(name, "the reflectance of a textured material (its texture replaces it)");
    any |= changed;
    if (roughnessDifferentiable(base.materials[m])) {
      double du = 0, dv = 0;
      for (size_t k = 0; k < scenes.size(); ++k) {
        du += weights[k] * scenes[k]->materials[m].alphaU;
        dv += weights[k] * scenes[k]->materials[m].alphaV;
      }
      if (du != 0 || dv != 0) {
        t.roughness[m].push_back({slot, static_cast<float>(du), static_cast<float>(dv)});
        any = true;
      }
    }
    if (!base.materials[m].reradiation) continue;
    MatrixTangent mt;
    mt.slot = slot;
    mt.cells.assign(static_cast<size_t>(ReradiationMatrix::kBins) * ReradiationMatrix::kBins, 0.0f);
    bool matrixChanged = false;
    constexpr int n = ReradiationMatrix::kBins;
    for (int i = 0; i < n; ++i)
      for (int o = i + 1; o < n; ++o) {
        double sum = 0, size = 0;
        for (size_t k = 0; k < scenes.size(); ++k) {
          const double v = (*scenes[k]->materials[m].reradiation)(i, o);
          sum += weights[k] * v;
          size = std::max(size, std::abs(weights[k] * v));
        }
        // Beyond rounding only: a cell the parameter does not reach stays 0 (else every cell
        // of every slot is looked up at every fluorescent vertex).
        if (!(std::abs(sum) > 1e-9 * size)) continue;
        matrixChanged = true;
        mt.cells[static_cast<size_t>(i) * n + o] = static_cast<float>(sum);
      }
    for (int o = 0; o < n; ++o) {
      double scale = 0, constant = 0, size = 0;
      for (size_t k = 0; k < scenes.size(); ++k) {
        const ReradiationMatrix& r = *scenes[k]->materials[m].reradiation;
        const double c = r.elastic(o, 0.0), s1 = r.elastic(o, 1.0) - c;
        scale += weights[k] * s1;
        constant += weights[k] * c;
        size = std::max({size, std::abs(weights[k] * s1), std::abs(weights[k] * c)});
      }
      if (!(std::abs(scale) > 1e-9 * size)) scale = 0;
      if (!(std::abs(constant) > 1e-9 * size)) constant = 0;
      if (scale == 0 && constant == 0) continue;
      matrixChanged = true;
      mt.elasticScale[static_cast<size_t>(o)] = static_cast<float>(scale);
      mt.elasticConstant[static_cast<size_t>(o)] = static_cast<float>(constant);
    }
    if (matrixChanged) t.reradiation[m].add(std::move(mt));
    any |= matrixChanged;
  }
  for (size_t k = 0; k < base.media.size(); ++k) {
    MediumTangent mt;
    mt.slot = slot;
    bool changed = false, part = false;
    std::vector<const Spectrum*> spectra;
    for (const RenderScene* sc : scenes) spectra.push_back(&sc->media[k].sigmaA);
    mt.sigmaA = Spectrum(stencil(spectra, weights, part));
    changed |= part;
    spectra.clear();
    for (const RenderScene* sc : scenes) spectra.push_back(&sc->media[k].sigmaS);
    mt.sigmaS = Spectrum(stencil(spectra, weights, part));
    changed |= part;
    // Scalars and the dye's tables: sum_i w_i x_i, "changed" beyond rounding.
    auto combine = [&](auto&& get) {
      double sum = 0, size = 0;
      for (size_t i = 0; i < scenes.size(); ++i) {
        const double v = get(scenes[i]->media[k]);
        sum += weights[i] * v;
        size = std::max(size, std::abs(weights[i] * v));
      }
      if (std::abs(sum) > 1e-9 * size && sum != 0) changed = true;
      return static_cast<float>(sum);
    };
    mt.g = combine([](const HomogeneousMedium& m) { return m.g; });
    mt.dyePeak = combine([](const HomogeneousMedium& m) { return m.dyePeak; });
    if (base.media[k].dye) {
      constexpr int n = ReradiationMatrix::kBins;
      mt.dyeCells.assign(static_cast<size_t>(n) * n, 0.0f);
      for (int o = 0; o < n; ++o) {
        mt.dyeAbsorptance[static_cast<size_t>(o)] =
            combine([o](const HomogeneousMedium& m) { return m.dye->absorptance(o); });
        mt.dyeColumnSum[static_cast<size_t>(o)] =
            combine([o](const HomogeneousMedium& m) { return m.dye->columnSum(o); });
        for (int i = 0; i < o; ++i)
          mt.dyeCells[static_cast<size_t>(i) * n + o] =
              combine([i, o](const HomogeneousMedium& m) { return (*m.dye)(i, o); });
      }
    }
    if (changed) t.media[k].push_back(std::move(mt));
    any |= changed;
  }
  for (size_t e = 0; e < base.emission.size(); ++e)
    any |=
        addSpectrumTangent(t.emission[e], slot, scenes, weights,
                           [e](const RenderScene& s) -> const Spectrum& { return s.emission[e]; });
  for (size_t l = 0; l < base.lights.size(); ++l)
    if (differentiatedLightSpectrum(base.lights[l]))
      any |= addSpectrumTangent(t.lights[l], slot, scenes, weights,
                                [l](const RenderScene& s) -> const Spectrum& {
                                  return *differentiatedLightSpectrum(s.lights[l]);
                                });
  if (base.background)
    any |=
        addSpectrumTangent(t.background, slot, scenes, weights,
                           [](const RenderScene& s) -> const Spectrum& { return *s.background; });
  t.slotNames.push_back(name);
  if (!any) t.inert.push_back(slot);
  return slot;
}

namespace {

// Adds one slot per value of the one per-material grid of values (a texture's texels, a
// concentration map) that differs between base and changed. `grid` describes it for a
// material: how many values it holds (0: none differentiable), whether the two materials
// differ in it, and the first-slot table it is recorded in; `what` names it in messages.
struct GridOfValues {
  const char* what;     ///< "texture", "concentration map"
  const char* mismatch; ///< why two grids cannot be differenced
  bool texture;         ///< otherMaterialChange's allowance
  std::vector<int64_t> SceneTangents::*firstSlot;
  size_t (*count)(const Material&);
  bool (*differs)(const Material&, const Material&);
};

uint32_t addGridSlots(SceneTangents& t, const std::string& name, const RenderScene& base,
                      const RenderScene& changed, const GridOfValues& grid) {
  if (changed.materials.size() != base.materials.size())
    notDifferentiated(name, "the scene's structure");
  const uint32_t first = t.slots();
  bool any = false;
  for (size_t m = 0; m < base.materials.size(); ++m) {
    const Material &a = base.materials[m], &b = changed.materials[m];
    const std::string other = otherMaterialChange(a, b, grid.texture, !grid.texture);
    if (!other.empty()) notDifferentiated(name, other);
    if (!grid.differs(a, b)) continue;
    const size_t n = grid.count(a);
    if (n == 0 || grid.count(b) != n) notDifferentiated(name, grid.mismatch);
    if (any) notDifferentiated(name, std::string("more than one material's ") + grid.what);
    (t.*grid.firstSlot)[m] = t.slots();
    for (size_t q = 0; q < n; ++q) t.slotNames.push_back(name + "[" + std::to_string(q) + "]");
    any = true;
  }
  if (!any) notDifferentiated(name, std::string("no ") + grid.what + " the scene renders");
  return first;
}

} // namespace

uint32_t addTextureSlots(SceneTangents& t, const std::string& name, const RenderScene& base,
                         const RenderScene& changed) {
  static const GridOfValues grid{
      "texture",
      "a texture that is not a spectral image of the same size (an sRGB texture's or the "
      "chart's texels are not differentiated)",
      true,
      &SceneTangents::textureFirstSlot,
      [](const Material& m) { return m.texture ? m.texture->valueCount() : size_t{0}; },
      [](const Material& a, const Material& b) {
        return a.texture && b.texture && !a.texture->sameAs(*b.texture);
      }};
  return addGridSlots(t, name, base, changed, grid);
}

namespace {

// What differs between `changed` and `base`, as the tangents of one slot (checked as any slot's:
// a change of what is not differentiated throws, naming `name`).
SceneTangents changeOf(const std::string& name, const RenderScene& base,
                       const RenderScene& changed) {
  SceneTangents probe = SceneTangents::sizedFor(base);
  const RenderScene* pair[] = {&changed, &base};
  const double unit[] = {1.0, -1.0};
  addTangentSlot(probe, name, base, pair, unit);
  return probe;
}

// True when no entry of the per-material (or per-emitter, ...) tangents holds a slot.
template <class V>
bool emptyAll(const V& v) {
  return std::all_of(v.begin(), v.end(), [](const auto& x) { return x.empty(); });
}

} // namespace

std::optional<uint32_t> addMeasuredCellSlots(SceneTangents& t, const std::string& name,
                                             const RenderScene& base, const RenderScene& changed,
                                             const MeasuredResampling& map,
                                             std::span<const double> cells) {
  constexpr int n = ReradiationMatrix::kBins;
  // What moving every cell changed: the structure is checked as for any slot; only surfaces'
  // matrices may differ (a medium's dye, or anything else, goes per cell).
  const SceneTangents probe = changeOf(name, base, changed);
  if (!emptyAll(probe.reflectance) || !emptyAll(probe.roughness) || !emptyAll(probe.emission) ||
      !emptyAll(probe.lights) || !emptyAll(probe.media) || !probe.background.empty())
    return std::nullopt;
  // The map applied to the cells must give each such material's matrix as it was resolved.
  std::vector<double> resampled(static_cast<size_t>(n) * n + n, 0.0);
  for (const MeasuredResampling::Term& term : map.terms)
    resampled[term.output] += term.w * cells[term.input];
  std::vector<size_t> materials;
  for (size_t m = 0; m < base.materials.size(); ++m) {
    if (probe.reradiation[m].empty()) continue;
    const ReradiationMatrix& r = *base.materials[m].reradiation;
    if (!r.measured()) return std::nullopt;
    auto near = [](double a, double b) {
      return std::abs(a - b) <= 1e-9 * std::max(std::abs(a), std::abs(b)) + 1e-300;
    };
    for (int i = 0; i < n; ++i)
      for (int o = i + 1; o < n; ++o)
        if (!near(r(i, o), resampled[static_cast<size_t>(i) * n + o])) return std::nullopt;
    if (!r.elasticFromReflectance())
      for (int o = 0; o < n; ++o)
        if (!near(r.elastic(o, 0.0), resampled[MeasuredResampling::diagonal(o)]))
          return std::nullopt;
    materials.push_back(m);
  }
  if (materials.empty()) return std::nullopt;
  // Each cell's column of the map (the terms regrouped by input cell).
  std::vector<uint32_t> start(cells.size() + 1, 0);
  for (const MeasuredResampling::Term& term : map.terms) ++start[term.input + 1];
  for (size_t q = 0; q < cells.size(); ++q) start[q + 1] += start[q];
  std::vector<const MeasuredResampling::Term*> byInput(map.terms.size());
  std::vector<uint32_t> next(start.begin(), start.end() - 1);
  for (const MeasuredResampling::Term& term : map.terms) byInput[next[term.input]++] = &term;
  const uint32_t first = t.slots();
  std::vector<std::pair<uint32_t, float>> cellTerms, elasticTerms;
  for (size_t q = 0; q < cells.size(); ++q) {
    const uint32_t slot = t.slots();
    t.slotNames.push_back(name + "[" + std::to_string(q) + "]");
    bool any = false;
    for (size_t m : materials) {
      cellTerms.clear();
      elasticTerms.clear();
      const bool elastic = !base.materials[m].reradiation->elasticFromReflectance();
      for (uint32_t k = start[q]; k < start[q + 1]; ++k) {
        const MeasuredResampling::Term& term = *byInput[k];
        if (term.output < MeasuredResampling::diagonal(0))
          cellTerms.emplace_back(term.output, static_cast<float>(term.w));
        else if (elastic)
          elasticTerms.emplace_back(term.output - MeasuredResampling::diagonal(0),
                                    static_cast<float>(term.w));
      }
      if (cellTerms.empty() && elasticTerms.empty()) continue;
      t.reradiation[m].addSparse(slot, cellTerms, elasticTerms);
      any = true;
    }
    if (!any) t.inert.push_back(slot);
  }
  return first;
}

std::optional<uint32_t> addTableKnotSlots(SceneTangents& t, const std::string& name,
                                          const RenderScene& base, const RenderScene& changed,
                                          std::span<const double> values,
                                          std::span<const double> moved) {
  if (values.empty() || moved.size() != values.size()) return std::nullopt;
  const SceneTangents probe = changeOf(name, base, changed);
  if (!emptyAll(probe.reradiation) || !emptyAll(probe.roughness) || !emptyAll(probe.media))
    return std::nullopt;
  // The spectra the knots reach, each checked to be c times the knots in both scenes.
  struct Reached {
    SpectrumTangents* into;
    const TabulatedSpectrum* table;
    double c;
    size_t knots; ///< into's entry for the table
  };
  std::vector<Reached> reached;
  size_t top = 0;
  for (size_t k = 0; k < moved.size(); ++k)
    if (std::abs(moved[k]) > std::abs(moved[top])) top = k;
  auto reach = [&](const SpectrumTangents& located, SpectrumTangents& into, const Spectrum* a,
                   const Spectrum* b) {
    if (located.empty()) return true;
    if (!a || !b) return false;
    const auto* ta = std::get_if<TabulatedSpectrum>(&a->kind());
    const auto* tb = std::get_if<TabulatedSpectrum>(&b->kind());
    if (!ta || !tb || ta->nm.size() != values.size() || ta->nm != tb->nm ||
        ta->holdEnds != tb->holdEnds)
      return false;
    const double c = b->scale() * tb->value[top] / moved[top];
    const double tolerance = 1e-9 * std::abs(c * moved[top]);
    for (size_t k = 0; k < values.size(); ++k)
      if (std::abs(a->scale() * ta->value[k] - c * values[k]) > tolerance ||
          std::abs(b->scale() * tb->value[k] - c * moved[k]) > tolerance)
        return false;
    reached.push_back({&into, ta, c, into.knotsOf(*ta)});
    return true;
  };
  bool linear = moved[top] != 0;
  for (size_t m = 0; linear && m < base.materials.size(); ++m)
    linear = reach(probe.reflectance[m], t.reflectance[m], &base.materials[m].reflectance,
                   &changed.materials[m].reflectance);
  for (size_t e = 0; linear && e < base.emission.size(); ++e)
    linear = reach(probe.emission[e], t.emission[e], &base.emission[e], &changed.emission[e]);
  for (size_t l = 0; linear && l < base.lights.size(); ++l)
    linear = reach(probe.lights[l], t.lights[l], differentiatedLightSpectrum(base.lights[l]),
                   differentiatedLightSpectrum(changed.lights[l]));
  if (linear && base.background)
    linear = reach(probe.background, t.background, &*base.background, &*changed.background);
  if (!linear || reached.empty()) return std::nullopt;
  const uint32_t first = t.slots();
  for (size_t j = 0; j < values.size(); ++j) {
    const uint32_t slot = t.slots();
    t.slotNames.push_back(name + "[" + std::to_string(j) + "]");
    for (const Reached& r : reached) {
      if (r.into->addKnot(slot, r.knots, j, static_cast<float>(r.c))) continue;
      TabulatedSpectrum hat = *r.table;
      std::fill(hat.value.begin(), hat.value.end(), 0.0);
      hat.value[j] = r.c;
      r.into->add(slot, Spectrum(std::move(hat)));
    }
  }
  return first;
}

uint32_t addConcentrationSlots(SceneTangents& t, const std::string& name, const RenderScene& base,
                               const RenderScene& changed) {
  static const GridOfValues grid{
      "concentration map",
      "whether a concentration map is used, or its size",
      false,
      &SceneTangents::concentrationFirstSlot,
      [](const Material& m) {
        return m.concentration ? m.concentration->values.size() : size_t{0};
      },
      [](const Material& a, const Material& b) { return concentrationDiffers(a, b); }};
  return addGridSlots(t, name, base, changed, grid);
}

} // namespace nx
