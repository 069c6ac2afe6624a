// Niixtracer's surfaces: (1 - r) rho * ideal mirror + r rho / pi, one model under six names that
// differ in their default r (matte, diffuse and default 1, plastic 0.7, metal 0.3, mirror 0),
// made energy-conserving (each lobe drawn with its weight; docs/materials.md): their
// parameters, build and sampling (below; dispatched from bsdf.cpp).

#include "integrators/materials/bsdf.h"
#include "integrators/materials/fresnel.h"
#include "integrators/materials/material_kind.h"
#include "integrators/sampling.h"

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

// ---- evaluation (SurfaceBsdf's lobes of this kind) ----

// (1 - r) rho * mirror + r rho / pi, lobe chosen with probabilities 1 - r and r: either way
// the weight is rho (Niixtracer's "roughness" mixture, made energy-conserving).
bool SurfaceBsdf::sampleMixture(float uLobe, Sample2 u, BsdfSample& out) const {
  if (dot(wo_, n_) <= 0) return false;
  const float r = material_->roughness;
  if (uLobe < r) {
    const Frame frame = Frame::fromNormal(n_);
    const Vec3 local = sampleCosineHemisphere(u);
    if (local.z <= 0) return false;
    out.wi = frame.toWorld(local);
    out.pdf = r * cosineHemispherePdf(local.z);
    out.specular = false;
  } else {
    out.wi = reflect(wo_, n_);
    out.pdf = 0;
    out.specular = true;
  }
  // A direction the shading frame allows below the geometric surface is absorbed.
  if (dot(out.wi, ng_) <= 0) return false;
  out.weight = rho_;
  out.terminateSecondary = false;
  out.eta = 1;
  return true;
}

} // namespace nx
