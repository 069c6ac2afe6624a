#include "io/aov_names.h"

#include "io/spectral_exr.h"

namespace nx {
namespace {

struct AovInfo {
  AovKind kind;
  const char* name;
};
constexpr AovInfo kInfo[] = {
    {AovKind::Normals, "normals"},   {AovKind::GeometricNormals, "geometric_normals"},
    {AovKind::Position, "position"}, {AovKind::Uv, "uv"},
    {AovKind::Albedo, "albedo"},     {AovKind::Fluorescence, "fluorescence"}};

// The band's channel name after its component ("550,000000nm").
std::string bandSuffix(const Sensor& bands, int b) {
  const std::string full = spectralChannelName(bands.channelNm(b)); // "S0.550,000000nm"
  return full.substr(full.find('.') + 1);
}

} // namespace

const char* aovName(AovKind k) {
  for (const AovInfo& i : kInfo)
    if (i.kind == k) return i.name;
  return "";
}

std::optional<AovKind> aovKindNamed(const std::string& name) {
  for (const AovInfo& i : kInfo)
    if (name == i.name) return i.kind;
  return std::nullopt;
}

std::vector<std::string> aovChannelNames(AovKind k, const Sensor& bands) {
  switch (k) {
  case AovKind::Normals:
  case AovKind::GeometricNormals:
  case AovKind::Position:
    return {"X", "Y", "Z"};
  case AovKind::Uv:
    return {"U", "V"};
  case AovKind::Albedo: {
    std::vector<std::string> out;
    for (int b = 0; b < bands.count(); ++b) out.push_back("T." + bandSuffix(bands, b));
    return out;
  }
  case AovKind::Fluorescence: {
    std::vector<std::string> out;
    for (int b = 0; b < bands.count(); ++b) out.push_back("absorption.T." + bandSuffix(bands, b));
    for (int b = 0; b < bands.count(); ++b) out.push_back("emission.S0." + bandSuffix(bands, b));
    return out;
  }
  }
  return {};
}

int aovChannelCount(AovKind k, int bands) {
  return k == AovKind::Albedo         ? bands
         : k == AovKind::Fluorescence ? 2 * bands
         : k == AovKind::Uv           ? 2
                                      : 3;
}

} // namespace nx
