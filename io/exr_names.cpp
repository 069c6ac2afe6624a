#include "io/exr_names.h"

#include <algorithm>

#include "core/error.h"
#include "io/light_layer_name.h"
#include "io/relight_channels.h"
#include "io/spectral_exr.h"
#include "spectra/spectrum.h"

namespace nx {

size_t longestExrNameOfLightGroup(const std::string& group) {
  // Every band and excitation wavelength lies within the traced range, and the channels write
  // them with six decimals: the range's end has the longest text.
  const std::string band = spectralChannelName(kTraceMaxNm);
  const std::string wavelength = band.substr(band.find('.') + 1);
  const std::string layer = kVariancePrefix + lightLayerName(group) + "." + band;
  const std::string transport =
      kHalfDifferencePrefix +
      relightChannelText(group + ".65535." + kRelightFluorescedLayer, wavelength, wavelength);
  const std::string attribute = kRelightGuideAttribute + group + ".65535.8";
  return std::max({layer.size(), transport.size(), attribute.size()});
}

size_t longestLightGroupName() {
  return kMaxExrNameBytes - longestExrNameOfLightGroup("");
}

void checkExrName(const std::string& path, const std::string& name, const char* what) {
  if (name.empty() || name.size() > kMaxExrNameBytes)
    throw Error(path + ": expected " + what + " names of 1-" + std::to_string(kMaxExrNameBytes) +
                " bytes (what OpenEXR stores), found one of " + std::to_string(name.size()) +
                " bytes: '" + name.substr(0, 60) + (name.size() > 60 ? "...'" : "'"));
}

} // namespace nx
