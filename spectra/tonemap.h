#pragma once
// Tone mapping of linear sRGB images to 8-bit sRGB previews.

#include <cstdint>
#include <vector>

#include "spectra/colour.h"

namespace nx {

/// Parameters of Reinhard et al.'s global photographic operator (SIGGRAPH 2002).
struct ReinhardSettings {
  double key = 0.18;         ///< middle-grey key value a
  double whiteLuminance = 0; ///< L_white after scaling; 0 = the image's largest (eq. 4)
};

/// Luminance of linear sRGB (Rec. 709 weights).
inline double luminance(const Rgb& c) {
  return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

/// Log-average luminance exp(mean(log(delta + L))) over pixels with finite luminance,
/// delta = 1e-6 (Reinhard 2002, eq. 1).
double logAverageLuminance(const std::vector<Rgb>& image);

/// Reinhard 2002 global operator (eqs. 1, 2, 4) on luminance, colour kept by scaling RGB,
/// then clamping to [0, 1], the sRGB transfer function and rounding to 8 bits. Returns
/// interleaved RGB bytes. Negative and non-finite values become 0.
std::vector<uint8_t> tonemapReinhard(const std::vector<Rgb>& image, const ReinhardSettings& s);

} // namespace nx
