#pragma once
// The test scale: NX_TEST_SCALE=K (a whole number from 1 to 64; 1 when unset) divides the sample
// counts of the long statistical tests by K and widens their power requirement by 2.5 sqrt(K):
// sqrt(K) is the growth of a Monte Carlo standard error at 1/K of the samples, 2.5 the spread of a
// standard error estimated from a few seeds at one or two samples each (ratios up to 1.54 were
// seen at K = 8). A test's power is its design, held at K = 1 by the Release pass. Their
// agreement checks stay z-tests in standard errors, so a wrong answer fails at any scale. CI's
// sanitizer pass runs them at K = 8 (docs/reliability.md, "CI time"): AddressSanitizer and
// UndefinedBehaviorSanitizer find faults at any sample count.

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace nx::test {

/// The scale K from NX_TEST_SCALE (1 when unset); anything but a whole number 1-64 throws.
inline int testScale() {
  static const int scale = [] {
    const char* v = std::getenv("NX_TEST_SCALE");
    if (v == nullptr || *v == '\0') return 1;
    char* end = nullptr;
    const long k = std::strtol(v, &end, 10);
    if (*end != '\0' || k < 1 || k > 64)
      throw std::invalid_argument("NX_TEST_SCALE: expected a whole number from 1 to 64, found '" +
                                  std::string(v) + "'");
    return static_cast<int>(k);
  }();
  return scale;
}

/// n samples (or trials) at the test scale: n / K, at least 1.
inline int scaledSamples(int n) {
  return std::max(1, n / testScale());
}

/// A required relative standard error at the test scale: power at K = 1, else power * 2.5 sqrt(K).
inline double scaledPower(double power) {
  const int k = testScale();
  return k == 1 ? power : power * 2.5 * std::sqrt(double(k));
}

/// A required separation of `sigmas` standard errors at the test scale: sigmas / sqrt(K), at least
/// 5 (what an agreement check within 5 standard errors needs to fail).
inline double scaledSeparation(double sigmas) {
  return std::max(5.0, sigmas / std::sqrt(double(testScale())));
}

} // namespace nx::test
