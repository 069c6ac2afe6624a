#include "spectra/named_spectra.h"

#include <array>
#include <utility>

#include "spectra/colorchecker.h"

namespace nx {
namespace {
constexpr std::array<std::pair<const char*, double>, 7> kColourPeaks{{{"red", 680},
                                                                      {"orange", 620},
                                                                      {"yellow", 600},
                                                                      {"green", 545},
                                                                      {"blue", 460},
                                                                      {"purple", 420},
                                                                      {"uv", 360}}};
} // namespace

std::optional<Spectrum> namedReflectance(const std::string& name) {
  for (const auto& [n, peak] : kColourPeaks)
    if (name == n) return Spectrum(GaussianSpectrum{peak, 34.0, 1.0});
  if (name == "const") return Spectrum(ConstantSpectrum{1.0});
  if (name == "null") return Spectrum(ConstantSpectrum{0.0});
  if (name == "gray") return Spectrum(ConstantSpectrum{0.5});
  if (name.rfind("colorchecker:", 0) == 0) return colorCheckerPatch(name.substr(13));
  return std::nullopt;
}

std::optional<double> namedAbsorptionPeak(const std::string& name) {
  if (name == "uv") return 370.0;
  for (const auto& [n, peak] : kColourPeaks)
    if (name == n) return peak;
  return std::nullopt;
}

} // namespace nx
