#pragma once
// Every lane at one wavelength with density 1, for tests of per-lane routines.

#include "spectra/sampled_wavelengths.h"

namespace nx::test {

/// kLanes lanes at `nm`, each with pdf 1.
inline SampledWavelengths flatWavelengths(float nm) {
  SampledWavelengths w;
  for (int i = 0; i < kLanes; ++i) w.lambda[i] = nm, w.pdf[i] = 1;
  return w;
}

} // namespace nx::test
