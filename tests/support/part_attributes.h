#pragma once
// The attributes nxrender writes on an image for nxmerge (sampler, render key, seed, bands,
// sample range), for tests that merge images rendered in memory.

#include <cstdint>
#include <string>

#include "io/spectral_exr.h"

namespace nx::test {

/// Sets them for samples [first, first + count) with the stratified sampler and `seed`.
inline void setPartAttributes(SpectralImage& img, uint32_t seed, int first, int count) {
  img.attributes["nxrender.sampler"] = "stratified";
  img.attributes["nxrender.renderKey"] = "key";
  img.attributes["nxrender.seed"] = std::to_string(seed);
  img.attributes["nxrender.bands"] = img.bands.toString();
  img.attributes["nxrender.sampleRange"] =
      std::to_string(first) + ":" + std::to_string(first + count);
}

} // namespace nx::test
