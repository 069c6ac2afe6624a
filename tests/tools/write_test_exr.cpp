// Writes a small spectral EXR for command-line tests of the image tools: 4x3 pixels, bands
// 500:600:100, every value 1 except that `--nan` puts a NaN into the first band of pixel 0.
//
//   write_test_exr OUT.exr [--nan]
#include <cmath>
#include <cstdio>
#include <string>

#include "io/spectral_exr.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: write_test_exr OUT.exr [--nan]\n");
    return 2;
  }
  nx::SpectralImage img;
  img.width = 4;
  img.height = 3;
  img.bands = nx::SpectralBands::parse("500:600:100");
  const size_t pixels = 12;
  img.radiance.assign(pixels * 2, 1.0f);
  img.rgb.assign(pixels * 3, 1.0f);
  img.xyz.assign(pixels * 3, 1.0f);
  img.sampleCount.assign(pixels, 4);
  if (argc > 2 && std::string(argv[2]) == "--nan") img.radiance[0] = NAN;
  img.attributes["nxrender.bands"] = img.bands.toString();
  nx::writeSpectralExr(argv[1], img);
  return 0;
}
