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

/// A ground-truth layer (`--aov NAME`, Python `aovs=[NAME]`).
enum class AovKind : uint8_t {
  Normals,          ///< the shading normal, world space (X, Y, Z)
  GeometricNormals, ///< the geometric normal, world space (X, Y, Z)
  Position,         ///< the hit point, world space (X, Y, Z)
  Uv,               ///< the surface coordinates textures use (U, V)
  Albedo,           ///< per band: reflectance (matte) or directional albedo (other kinds)
  Fluorescence      ///< per band: the dye's absorption (photon yield) and emission spectra
};

/// Every kind, in the order their channels are stored.
inline constexpr AovKind kAovKinds[] = {AovKind::Normals,  AovKind::GeometricNormals,
                                        AovKind::Position, AovKind::Uv,
                                        AovKind::Albedo,   AovKind::Fluorescence};

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

} // namespace nx
