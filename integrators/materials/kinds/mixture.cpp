// Niixtracer's surfaces: (1 - r) rho * ideal mirror + r rho / pi, one model under six names that
// differ in their default r (matte, diffuse and default 1, plastic 0.7, metal 0.3, mirror 0),
// made energy-conserving (each lobe drawn with its weight; docs/materials.md). Evaluation:
// SurfaceBsdf's mixture lobes (materials/bsdf.cpp).

#include "integrators/materials/material_kind.h"

namespace nx {
namespace {

Material buildMixture(const MaterialKindSpec& kind, const ParameterSet& p,
                      const MaterialInputs& in) {
  Material m;
  m.kind = MaterialKind::Mixture;
  m.roughness = static_cast<float>(p.number("roughness").value_or(kind.numberDefault("roughness")));
  setSurfaceReflectance(m, p, in, false, "reflectance");
  setFluorescence(m, p, in);
  return m;
}

#define NX_MIXTURE_PARAMS(roughness)                                                               \
  {"color", "", ""}, {"reflectance", "", "albedo rho (required unless the object emits)"},         \
      {"roughness", roughness, ""}, {                                                              \
    "fluorescence", "", ""                                                                         \
  }

constexpr KindParameter kMatteParams[] = {NX_MIXTURE_PARAMS("1")};
constexpr KindParameter kPlasticParams[] = {NX_MIXTURE_PARAMS("0.7")};
constexpr KindParameter kMetalParams[] = {NX_MIXTURE_PARAMS("0.3")};
constexpr KindParameter kMirrorParams[] = {NX_MIXTURE_PARAMS("0")};
#undef NX_MIXTURE_PARAMS

constexpr std::pair<const char*, const char*> kRefusals[] = {
    {"alpha", "GGX roughness is for conductors and dielectrics; here <roughness> weighs the "
              "Lambertian lobe"},
    {"ior", "an index of refraction is for dielectrics and coated"},
    {"coating", "thin films lie on conductors and smooth dielectrics"}};

} // namespace

extern const MaterialKindSpec kMatteKind{"matte", "Lambertian (Niixtracer's mixture with r = 1)",
                                         kMatteParams, kRefusals, buildMixture};
extern const MaterialKindSpec kDiffuseKind{"diffuse", "the same as matte", kMatteParams, kRefusals,
                                           buildMixture};
extern const MaterialKindSpec kDefaultKind{"default", "the same as matte", kMatteParams, kRefusals,
                                           buildMixture};
extern const MaterialKindSpec kPlasticKind{
    "plastic", "Niixtracer's mixture with r = 0.7: mostly diffuse, some mirror", kPlasticParams,
    kRefusals, buildMixture};
extern const MaterialKindSpec kMetalKind{
    "metal",
    "Niixtracer's mixture with r = 0.3: mostly mirror, tinted by rho (physical metals: conductor)",
    kMetalParams, kRefusals, buildMixture};
extern const MaterialKindSpec kMirrorKind{"mirror",
                                          "an ideal mirror tinted by rho (the mixture with r = 0)",
                                          kMirrorParams, kRefusals, buildMixture};

} // namespace nx
