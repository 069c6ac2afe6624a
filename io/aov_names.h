#pragma once
// The ground-truth layers' names: the kinds (integrators/aov_layers.h evaluates them), their EXR
// layer names and channels (docs/datasets.md), declared once for the renderer, the EXR reader
// and writer, the merge and Python.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "spectra/sensor.h"

namespace nx {

/// How a ground-truth layer's channels are laid out: X, Y, Z; U, V; T.<band> per band;
/// absorption.T.<band> then emission.S0.<band>.
enum class AovLayout : uint8_t { Vector, Uv, PerBand, AbsorptionEmission };

/// The ground-truth layers, one line each, in the order their channels are stored:
/// X(Kind, "name", layout, "what it holds, for --help"). The enum, the names, the channels, the
/// option lists in messages and help are generated from it; the value is evaluated in
/// integrators/aov_layers.cpp (docs/architecture.md, "Adding a kind").
#define NX_AOV_LAYERS(X)                                                                           \
  X(Normals, "normals", Vector, "the shading normal, world space")                                 \
  X(GeometricNormals, "geometric_normals", Vector, "the geometric normal, world space")            \
  X(Position, "position", Vector, "the hit point, world space")                                    \
  X(Uv, "uv", Uv, "the surface coordinates textures use")                                          \
  X(Albedo, "albedo", PerBand,                                                                     \
    "reflectance, or the directional albedo of non-matte kinds, per band")                         \
  X(Fluorescence, "fluorescence", AbsorptionEmission,                                              \
    "the dye's photon yield per excitation wavelength and emission per nm")                        \
  /* (end of list) */

#define NX_AOV_ENUMERATOR(Kind, name, layout, doc) Kind,
/// A ground-truth layer (`--aov NAME`, Python `aovs=[NAME]`).
enum class AovKind : uint8_t { NX_AOV_LAYERS(NX_AOV_ENUMERATOR) };
#undef NX_AOV_ENUMERATOR

#define NX_AOV_KIND(Kind, name, layout, doc) AovKind::Kind,
/// Every kind, in the order their channels are stored.
inline constexpr AovKind kAovKinds[] = {NX_AOV_LAYERS(NX_AOV_KIND)};
#undef NX_AOV_KIND

/// The layer's name ("normals", "geometric_normals", "position", "uv", "albedo",
/// "fluorescence"): its EXR layer and its option value.
const char* aovName(AovKind k);
/// The kind named `name`, or none.
std::optional<AovKind> aovKindNamed(const std::string& name);
/// The layer's channels, after its "<name>." prefix: X, Y, Z; U, V; T.<band> for the albedo;
/// absorption.T.<band> then emission.S0.<band> for the fluorescence (band names as the
/// radiance's, e.g. "550,000000nm").
std::vector<std::string> aovChannelNames(AovKind k, const Sensor& bands);

/// Channels of kind k for `bands` output bands.
int aovChannelCount(AovKind k, int bands);

/// What layer k holds, one phrase (for --help).
const char* aovDoc(AovKind k);

/// The layer's channels' layout.
AovLayout aovLayout(AovKind k);

} // namespace nx
