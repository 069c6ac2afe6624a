#include "spectra/tonemap.h"

#include <algorithm>
#include <cmath>

namespace nx {

double logAverageLuminance(const std::vector<Rgb>& image) {
  double sum = 0;
  size_t n = 0;
  for (const auto& c : image) {
    const double y = luminance(c);
    if (!std::isfinite(y)) continue;
    sum += std::log(1e-6 + std::max(y, 0.0));
    ++n;
  }
  return n ? std::exp(sum / static_cast<double>(n)) : 0.0;
}

std::vector<uint8_t> tonemapReinhard(const std::vector<Rgb>& image, const ReinhardSettings& s) {
  const double avg = logAverageLuminance(image);
  const double scale = avg > 0 ? s.key / avg : 0.0;
  double white = s.whiteLuminance;
  if (white <= 0) {
    for (const auto& c : image) {
      const double y = luminance(c);
      if (std::isfinite(y)) white = std::max(white, scale * y);
    }
  }
  std::vector<uint8_t> out;
  out.reserve(image.size() * 3);
  for (const auto& c : image) {
    const double y = luminance(c);
    double factor = 0;
    if (std::isfinite(y) && y > 0) {
      const double l = scale * y;
      const double ld = white > 0 ? l * (1.0 + l / (white * white)) / (1.0 + l) : l / (1.0 + l);
      factor = ld / y;
    }
    for (double v : {c.r, c.g, c.b}) {
      double x = std::isfinite(v) ? std::clamp(v * factor, 0.0, 1.0) : 0.0;
      out.push_back(static_cast<uint8_t>(std::lround(255.0 * srgbEncode(x))));
    }
  }
  return out;
}

} // namespace nx
