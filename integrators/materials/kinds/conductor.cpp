// A metal: GGX microfacets (smooth when alpha is 0) with the exact Fresnel reflectance of its
// complex index eta + i k, a built-in measured metal or given spectra, optionally under a thin
// film on each microfacet. Evaluation: SurfaceBsdf's conductor lobes (bsdf.cpp).

#include <tuple>

#include "core/error.h"
#include "core/text_table.h"
#include "integrators/materials/material_kind.h"
#include "spectra/metals.h"
#include "spectra/spectrum_bounds.h"

namespace nx {
namespace {

std::string metalList() {
  std::string names;
  for (const std::string& n : metalNames()) names += (names.empty() ? "" : ", ") + n;
  return names;
}

Material buildConductor(const MaterialKindSpec&, const ParameterSet& p, const MaterialInputs& in) {
  Material m;
  m.kind = MaterialKind::Conductor;
  m.reflectance = Spectrum(ConstantSpectrum{1.0});
  const SpectrumDesc *eta = p.get<SpectrumDesc>("eta"), *k = p.get<SpectrumDesc>("k");
  if (const Parameter* metalParam = p.find("metal")) {
    if (eta || k)
      throw Error(metalParam->loc.str() + ": expected either <metal> or <eta> and <k>, found both");
    const std::string& name = std::get<std::string>(metalParam->value);
    const std::optional<MetalIndex> metal = namedMetal(name);
    if (!metal)
      throw Error(metalParam->loc.str() + ": expected a metal name (" + metalList() + "), found '" +
                  name + "'");
    m.conductorEta = metal->eta;
    m.conductorK = metal->k;
  } else {
    if (!eta || !k)
      throw Error(in.objectLoc.str() + ": expected <metal> (" + metalList() +
                  ") or both <eta> and <k> on a conductor, found " +
                  (eta ? "<eta> alone"
                   : k ? "<k> alone"
                       : "neither"));
    m.conductorEta = forRendering(in.spectrum(*eta, SpectrumRole::Coefficient));
    m.conductorK = forRendering(in.spectrum(*k, SpectrumRole::Coefficient));
    for (const auto& [sp, desc, what, lo] :
         {std::tuple{&m.conductorEta, eta, "eta", 1e-3}, std::tuple{&m.conductorK, k, "k", 0.0}}) {
      const SpectrumExtremes e = spectrumExtremes(*sp, kTraceMinNm, kTraceMaxNm);
      if (!(e.min >= lo && e.max <= 1e3))
        throw Error(desc->loc.str() + ": expected " + what + " within [" + numberText(lo) +
                    ", 1000] at every wavelength of " + tracedRange() + ", found " +
                    (std::isnan(e.min) ? std::string("a non-finite value")
                                       : numberText(e.min < lo ? e.min : e.max) + " at " +
                                             numberText(e.min < lo ? e.minNm : e.maxNm) + " nm") +
                    (e.min == 0 && lo > 0 ? " (a table is 0 beyond its rows; extrapolate=\"hold\" "
                                            "keeps its end values)"
                                          : ""));
    }
  }
  setGgxAlpha(m, p);
  setCoating(m, p, in);
  return m;
}

constexpr KindParameter kParams[] = {{"metal", "", "a built-in metal (or <eta> and <k>)"},
                                     {"eta", "", "with <k>, instead of <metal>"},
                                     {"k", "", "with <eta>, instead of <metal>"},
                                     {"alpha", "0", "GGX roughness (0: smooth)"},
                                     {"alpha_u", "", ""},
                                     {"alpha_v", "", ""},
                                     {"coating", "", "a thin film on each microfacet"}};

constexpr std::pair<const char*, const char*> kRefusals[] = {
    {"color", "its colour is its <metal> or <eta> and <k>"},
    {"reflectance", "its colour is its <metal> or <eta> and <k>"},
    {"roughness", "its roughness is <alpha>"},
    {"ior", "its index is <eta> and <k>"}};

} // namespace

extern const MaterialKindSpec kConductorKind{
    "conductor", "a metal: GGX microfacets and the exact Fresnel reflectance of eta + i k", kParams,
    kRefusals, buildConductor};

} // namespace nx
