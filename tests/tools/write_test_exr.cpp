// Writes a small spectral EXR for command-line tests of the image tools: 4x3 pixels, bands
// 500:600:100, every value 1. `--nan` puts a NaN into the first band of pixel 0; `--huge`
// makes the 4x3 pixels a crop of a 200000x200000 image (a part whose merge cannot fit).
//
//   write_test_exr OUT.exr [--nan | --huge]
#include <cmath>
#include <cstdio>
#include <string>

#include "io/spectral_exr.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: write_test_exr OUT.exr [--nan | --huge]\n");
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
  if (argc > 2 && std::string(argv[2]) == "--huge") img.fullWidth = img.fullHeight = 200000;
  img.attributes["nxrender.bands"] = img.bands.toString();
  img.attributes["nxrender.renderKey"] = "test";
  img.attributes["nxrender.seed"] = "0";
  img.attributes["nxrender.sampleRange"] = "0:4";
  nx::writeSpectralExr(argv[1], img);
  return 0;
}
