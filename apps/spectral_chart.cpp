#include "apps/spectral_chart.h"

#include <tbb/parallel_for.h>

#include <array>
#include <string>
#include <vector>

#include "spectra/colour.h"
#include "spectra/illuminants.h"
#include "spectra/named_spectra.h"

namespace nx {

SpectralImage renderSpectralChart(const SpectralBands& bands, int patch) {
  const std::array<const char*, 9> reflectances{"red",    "orange", "yellow", "green", "blue",
                                                "purple", "uv",     "gray",   "const"};
  const std::array<const char*, 4> illuminants{"D65", "A", "F11", "bl"};
  const int cols = static_cast<int>(reflectances.size());
  const int rows = static_cast<int>(illuminants.size());
  const int nBands = bands.count();

  SpectralImage img;
  img.width = cols * patch;
  img.height = rows * patch;
  img.bands = bands;
  img.radiance.assign(static_cast<size_t>(img.width) * img.height * nBands, 0.0f);
  img.rgb.assign(static_cast<size_t>(img.width) * img.height * 3, 0.0f);

  tbb::parallel_for(0, rows * cols, [&](int p) {
    const int row = p / cols, col = p % cols;
    const Spectrum light = *namedEmission(illuminants[row]);
    const Spectrum refl = *namedReflectance(reflectances[col]);
    std::vector<double> nm, value; // reflected radiance at 0.1 nm steps
    for (int i = 0; i <= 10 * (kCieMaxNm - 300); ++i) {
      const double l = 300.0 + 0.1 * i;
      nm.push_back(l);
      value.push_back(light(l) * refl(l));
    }
    const Spectrum reflected(TabulatedSpectrum{std::move(nm), std::move(value)});
    std::vector<float> bandValues(nBands);
    for (int b = 0; b < nBands; ++b)
      bandValues[b] = static_cast<float>(bandAverage(reflected, bands, b));
    const Rgb rgb = xyzToLinearSrgb(spectrumToXyz(reflected));
    for (int y = row * patch; y < (row + 1) * patch; ++y)
      for (int x = col * patch; x < (col + 1) * patch; ++x) {
        const size_t px = static_cast<size_t>(y) * img.width + x;
        for (int b = 0; b < nBands; ++b) img.radiance[px * nBands + b] = bandValues[b];
        img.rgb[px * 3 + 0] = static_cast<float>(std::max(rgb.r, 0.0));
        img.rgb[px * 3 + 1] = static_cast<float>(std::max(rgb.g, 0.0));
        img.rgb[px * 3 + 2] = static_cast<float>(std::max(rgb.b, 0.0));
      }
  });
  std::string names;
  for (const char* n : illuminants) names += std::string(names.empty() ? "" : ",") + n;
  img.attributes["nxrender.chartIlluminants"] = names;
  names.clear();
  for (const char* n : reflectances) names += std::string(names.empty() ? "" : ",") + n;
  img.attributes["nxrender.chartReflectances"] = names;
  return img;
}

} // namespace nx
