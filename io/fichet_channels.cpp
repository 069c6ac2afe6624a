// Spectral channel names of the Fichet et al. 2021 layout.

#include "io/fichet_channels.h"
#include "core/number_text.h"

#include <algorithm>
#include <map>
#include <regex>

namespace nx {

std::vector<FichetChannel> fichetSpectralChannels(const std::vector<std::string>& names,
                                                  std::string& kind) {
  // The reference reader's expression (the paper, section 3.1).
  static const std::regex pattern(
      R"(^((S([0-3]))|T)\.(\d*,?\d*([Ee][+-]?\d+)?)(Y|Z|E|P|T|G|M|k|h|da|d|c|m|u|n|p)?(m|Hz)$)");
  static const std::map<std::string, double> prefix{
      {"Y", 1e24}, {"Z", 1e21}, {"E", 1e18}, {"P", 1e15}, {"T", 1e12}, {"G", 1e9},
      {"M", 1e6},  {"k", 1e3},  {"h", 1e2},  {"da", 1e1}, {"", 1},     {"d", 1e-1},
      {"c", 1e-2}, {"m", 1e-3}, {"u", 1e-6}, {"n", 1e-9}, {"p", 1e-12}};
  std::vector<FichetChannel> emissive, reflective;
  for (const std::string& name : names) {
    std::smatch m;
    if (!std::regex_match(name, m, pattern)) continue;
    const bool isT = m[1] == "T";
    if (!isT && m[3] != "0") continue; // polarisation components S1-S3 are not radiance
    std::string number = m[4];
    std::replace(number.begin(), number.end(), ',', '.');
    if (number.empty() || number == ".") continue;
    const char* end = nullptr;
    const double v = strtodC(number.c_str(), &end);
    if (*end != '\0' || !(v > 0)) continue;
    const double si = v * prefix.at(m[6]);
    const double nm = m[7] == "Hz" ? 299792458.0 / si * 1e9 : si * 1e9;
    (isT ? reflective : emissive).push_back({name, nm});
  }
  std::vector<FichetChannel>& chosen = emissive.empty() ? reflective : emissive;
  kind = chosen.empty() ? "" : emissive.empty() ? "T" : "S0";
  std::sort(chosen.begin(), chosen.end(),
            [](const FichetChannel& a, const FichetChannel& b) { return a.nm < b.nm; });
  return chosen;
}

} // namespace nx
