// A thin glass wall (two parallel faces): Fresnel reflection with the internal reflections
// summed, straight transmission, no refraction offset. Evaluation:
// SurfaceBsdf::sampleThinDielectric (bsdf.cpp).

#include "integrators/materials/material_kind.h"

namespace nx {
namespace {

Material buildThinGlass(const MaterialKindSpec& kind, const ParameterSet& p,
                        const MaterialInputs& in) {
  Material m;
  m.kind = MaterialKind::ThinDielectric;
  const IorDesc* ior = p.get<IorDesc>("ior");
  m.ior = ior ? in.ior(*ior) : IorModel::constant(kind.numberDefault("ior"));
  setSurfaceReflectance(m, p, in, true, "transmission tint");
  return m;
}

constexpr KindParameter kParams[] = {
    {"color", "", ""}, {"reflectance", "1", "transmission tint"}, {"ior", "1.5", ""}};

constexpr std::pair<const char*, const char*> kRefusals[] = {
    {"alpha", "a thin wall stays smooth"},
    {"fluorescence", "fluorescent dielectrics need media: a <medium> with a dye"}};

} // namespace

extern const MaterialKindSpec kThinGlassKind{
    "thin_glass", "a thin glass wall: reflects and transmits straight through, without refraction",
    kParams, kRefusals, buildThinGlass};

} // namespace nx
