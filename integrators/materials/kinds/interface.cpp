// The boundary of a medium with the same index on both sides: light passes unchanged (no
// reflection, no refraction). Its one lobe (straight on) is a line of SurfaceBsdf::sample
// (bsdf.cpp).

#include "core/error.h"
#include "integrators/materials/material_kind.h"

namespace nx {
namespace {

Material buildInterface(const MaterialKindSpec&, const ParameterSet&, const MaterialInputs& in) {
  if (in.emitter)
    throw Error(in.objectLoc.str() +
                ": expected no <emission> on an interface (it only bounds a medium), found one");
  Material m;
  m.kind = MaterialKind::Interface;
  m.reflectance = Spectrum(ConstantSpectrum{1.0});
  return m;
}

constexpr std::pair<const char*, const char*> kRefusals[] = {
    {"color", "it only bounds a medium"},
    {"reflectance", "it only bounds a medium"},
    {"fluorescence", "it only bounds a medium"}};

} // namespace

extern const MaterialKindSpec kInterfaceKind{
    "interface",
    "an index-matched boundary of a <medium>: light passes unchanged",
    {},
    kRefusals,
    buildInterface};

} // namespace nx
