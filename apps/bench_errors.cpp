#include "apps/bench_errors.h"

#include <algorithm>
#include <cmath>

namespace nx::bench {

ImageErrors compareWithReference(const Film& f, const SpectralImage& ref) {
  ImageErrors e;
  const int nb = ref.bands.count();
  const double n = static_cast<double>(ref.width) * ref.height;
  double se = 0, meanY = 0;
  std::vector<double> bandSe(static_cast<size_t>(nb), 0.0), bandMean(static_cast<size_t>(nb), 0.0);
  for (int y = 0; y < ref.height; ++y)
    for (int x = 0; x < ref.width; ++x) {
      const size_t i = static_cast<size_t>(y) * ref.width + x;
      const double d = f.xyzMean(x, y).y - ref.xyz[i * 3 + 1];
      se += d * d;
      meanY += ref.xyz[i * 3 + 1];
      for (int b = 0; b < nb; ++b) {
        const double db = f.bandMean(x, y, b) - ref.radiance[i * nb + b];
        bandSe[b] += db * db;
        bandMean[b] += ref.radiance[i * nb + b];
      }
    }
  e.rmseY = std::sqrt(se / n);
  e.relY = e.rmseY / (meanY / n);
  for (int b = 0; b < nb; ++b) {
    e.bandRmse.push_back(std::sqrt(bandSe[b] / n));
    const double rel = bandMean[b] > 0 ? e.bandRmse.back() / (bandMean[b] / n) : 0.0;
    e.meanBandRel += rel / nb;
    e.maxBandRel = std::max(e.maxBandRel, rel);
  }
  return e;
}

} // namespace nx::bench
