#pragma once
// The spectral channel names of the layout of Fichet, Pacanowski & Wilkie (JCGT 10(3), 2021):
// "S0.550,5nm", "T.5.5e-7m", "S0.545THz": a Stokes component (S0-S3) or T (reflective), the
// value with a comma as decimal separator, an SI prefix and m or Hz.

#include <string>
#include <vector>

namespace nx {

/// One spectral channel of a file.
struct FichetChannel {
  std::string name; ///< as in the file
  double nm = 0;    ///< its wavelength (a frequency converted with c)
};

/// The channels of one kind among `names`: Stokes component 0 (emissive) when there are any,
/// else T (reflective); sorted by wavelength. Names matching neither (R, G, B, Variance.*,
/// S1-S3) are skipped; `kind` is set to "S0", "T" or "" (none found).
std::vector<FichetChannel> fichetSpectralChannels(const std::vector<std::string>& names,
                                                  std::string& kind);

} // namespace nx
