// Dielectrics: exact Fresnel reflection and refraction with total internal reflection, smooth
// or rough (GGX microfacets, Walter et al. 2007), dispersive through a Cauchy or Sellmeier
// index, optionally under a thin-film coating (smooth only). Four names differing in their
// default index. Evaluation: SurfaceBsdf::sampleDielectric (bsdf.cpp) and the rough lobes
// (bsdf_rough_dielectric.cpp).

#include <algorithm>

#include "core/error.h"
#include "integrators/materials/material_kind.h"

namespace nx {
namespace {

Material buildDielectric(const MaterialKindSpec& kind, const ParameterSet& p,
                         const MaterialInputs& in) {
  Material m;
  m.kind = MaterialKind::Dielectric;
  const IorDesc* ior = p.get<IorDesc>("ior");
  m.ior = ior ? in.ior(*ior) : IorModel::constant(kind.numberDefault("ior"));
  setGgxAlpha(m, p);
  setSurfaceReflectance(m, p, in, true, "transmission tint");
  if (const Parameter* c = p.find("coating")) {
    // A thin film needs a smooth interface to lie on.
    if (std::max(m.alphaU, m.alphaV) > 0)
      throw Error(c->loc.str() +
                  ": expected a <coating> on a smooth dielectric, found it on a rough one "
                  "(<alpha>)");
    setCoating(m, p, in);
  }
  return m;
}

#define NX_DIELECTRIC_PARAMS(ior)                                                                  \
  {"color", "", ""}, {"reflectance", "1", "transmission tint"}, {"ior", ior, ""},                  \
      {"alpha", "0", "GGX roughness (0: smooth; a frosted surface above)"}, {"alpha_u", "", ""},   \
      {"alpha_v", "", ""}, {                                                                       \
    "coating", "", "a thin film on a smooth surface"                                               \
  }

constexpr KindParameter kGlassParams[] = {NX_DIELECTRIC_PARAMS("1.5")};
constexpr KindParameter kDiamondParams[] = {NX_DIELECTRIC_PARAMS("2.418")};
constexpr KindParameter kTranslucentParams[] = {NX_DIELECTRIC_PARAMS("1.02")};
#undef NX_DIELECTRIC_PARAMS

constexpr std::pair<const char*, const char*> kRefusals[] = {
    {"fluorescence", "fluorescent dielectrics need media: a <medium> with a dye"},
    {"roughness", "a dielectric's roughness is <alpha>"}};

} // namespace

extern const MaterialKindSpec kGlassKind{"glass",
                                         "a dielectric of index 1.5 unless <ior> says otherwise",
                                         kGlassParams, kRefusals, buildDielectric};
extern const MaterialKindSpec kDiamondKind{"diamond", "a dielectric of index 2.418", kDiamondParams,
                                           kRefusals, buildDielectric};
extern const MaterialKindSpec kTranslucentKind{"translucent",
                                               "a dielectric of index 1.02 (Niixtracer's)",
                                               kTranslucentParams, kRefusals, buildDielectric};
extern const MaterialKindSpec kTransparentKind{"transparent", "the same as translucent",
                                               kTranslucentParams, kRefusals, buildDielectric};

} // namespace nx
