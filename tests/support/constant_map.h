#pragma once
// A spectral EXR in the project's layout whose every pixel and band holds one value: the
// environment maps and file examples of the light tests.

#include <gtest/gtest.h>

#include <string>

#include "io/spectral_exr.h"

namespace nx::test {

/// Writes `name` in the test directory: width x height pixels, bands START:END:STEP, every
/// radiance `value`; returns its path.
inline std::string writeConstantMap(const std::string& name, int width, int height,
                                    const std::string& bands, float value) {
  SpectralImage img;
  img.width = width, img.height = height;
  img.bands = Sensor(SpectralBands::parse(bands));
  const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
  img.radiance.assign(pixels * static_cast<size_t>(img.bands.count()), value);
  img.rgb.assign(pixels * 3, 0.5f);
  img.attributes["nxrender.bands"] = img.bands.toString();
  const std::string path = ::testing::TempDir() + "/" + name;
  writeSpectralExr(path, img);
  return path;
}

} // namespace nx::test
