#include "io/aov_names.h"

#include "io/spectral_exr.h"

namespace nx {
namespace {

struct AovInfo {
  AovKind kind;
  const char* name;
  AovLayout layout;
  const char* doc;
};
#define NX_AOV_INFO(Kind, name, layout, doc) {AovKind::Kind, name, AovLayout::layout, doc},
constexpr AovInfo kInfo[] = {NX_AOV_LAYERS(NX_AOV_INFO)};
#undef NX_AOV_INFO

const AovInfo& info(AovKind k) {
  return kInfo[static_cast<size_t>(k)];
}

// The band's channel name after its component ("550,000000nm").
std::string bandSuffix(const Sensor& bands, int b) {
  const std::string full = spectralChannelName(bands.channelNm(b)); // "S0.550,000000nm"
  return full.substr(full.find('.') + 1);
}

} // namespace

const char* aovName(AovKind k) {
  return info(k).name;
}

const char* aovDoc(AovKind k) {
  return info(k).doc;
}

AovLayout aovLayout(AovKind k) {
  return info(k).layout;
}

std::optional<AovKind> aovKindNamed(const std::string& name) {
  for (const AovInfo& i : kInfo)
    if (name == i.name) return i.kind;
  return std::nullopt;
}

std::vector<std::string> aovChannelNames(AovKind k, const Sensor& bands) {
  std::vector<std::string> out;
  switch (aovLayout(k)) {
  case AovLayout::Vector:
    return {"X", "Y", "Z"};
  case AovLayout::Uv:
    return {"U", "V"};
  case AovLayout::PerBand:
    for (int b = 0; b < bands.count(); ++b) out.push_back("T." + bandSuffix(bands, b));
    return out;
  case AovLayout::AbsorptionEmission:
    for (int b = 0; b < bands.count(); ++b) out.push_back("absorption.T." + bandSuffix(bands, b));
    for (int b = 0; b < bands.count(); ++b) out.push_back("emission.S0." + bandSuffix(bands, b));
    return out;
  }
  return out;
}

int aovChannelCount(AovKind k, int bands) {
  switch (aovLayout(k)) {
  case AovLayout::Vector:
    return 3;
  case AovLayout::Uv:
    return 2;
  case AovLayout::PerBand:
    return bands;
  case AovLayout::AbsorptionEmission:
    return 2 * bands;
  }
  return 0;
}

} // namespace nx
