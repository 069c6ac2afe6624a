// A Lambertian base (possibly fluorescent) under a smooth clear coat of constant index, the
// internal reflections between them summed. Evaluation: SurfaceBsdf's coated lobes
// (bsdf_coated_diffuse.cpp).

#include "core/error.h"
#include "integrators/materials/fresnel.h"
#include "integrators/materials/material_kind.h"

namespace nx {
namespace {

// The hemispherical (cosine-weighted) reflectance of a smooth interface of relative index n
// for diffuse light from inside: Fi = 1 - (1 - Fe) / n^2 with Fe = 2 integral_0^1 F(mu) mu dmu
// from outside (energy through the interface is the same both ways; radiance scales by n^2).
double internalDiffuseReflectance(double n) {
  double fe = 0;
  const int steps = 4000;
  for (int i = 0; i < steps; ++i) {
    const double mu = (i + 0.5) / steps;
    fe += 2 * fresnelDielectric(static_cast<float>(mu), static_cast<float>(n)) * mu / steps;
  }
  return 1 - (1 - fe) / (n * n);
}

Material buildCoated(const MaterialKindSpec& kind, const ParameterSet& p,
                     const MaterialInputs& in) {
  Material m;
  m.kind = MaterialKind::CoatedDiffuse;
  const IorDesc* ior = p.get<IorDesc>("ior");
  m.ior = ior ? in.ior(*ior) : IorModel::constant(kind.numberDefault("ior"));
  if (m.ior.dispersive())
    throw Error(ior->loc.str() + ": expected a constant <ior> for a coat (a number), found "
                                 "a dispersive one");
  m.coatInternalReflectance = static_cast<float>(internalDiffuseReflectance(m.ior.at(550)));
  setSurfaceReflectance(m, p, in, false, "reflectance");
  setFluorescence(m, p, in);
  return m;
}

constexpr KindParameter kParams[] = {{"color", "", ""},
                                     {"reflectance", "", "the base's albedo"},
                                     {"ior", "1.5", "the coat's index (a constant)"},
                                     {"fluorescence", "", "of the base"}};

constexpr std::pair<const char*, const char*> kRefusals[] = {
    {"roughness", "a Lambertian base under a smooth coat"},
    {"alpha", "its coat is smooth"},
    {"coating", "its coat is the clear coat; thin films lie on conductors and dielectrics"}};

} // namespace

extern const MaterialKindSpec kCoatedKind{
    "coated", "a Lambertian base under a smooth clear coat, internal reflections summed", kParams,
    kRefusals, buildCoated};

} // namespace nx
