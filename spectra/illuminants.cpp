#include "spectra/illuminants.h"

#include <cctype>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "core/text_table.h"
#include "spectra/cie.h"

namespace nx {

extern const char* const kCieDaylightCsv;
extern const char* const kCieFluorescentCsv;

namespace {

const NumberTable& daylightTable() {
  static const NumberTable t = parseNumberTable(kCieDaylightCsv, "cie_daylight.csv", true);
  return t;
}

const NumberTable& fluorescentTable() {
  static const NumberTable t = parseNumberTable(kCieFluorescentCsv, "cie_fluorescent.csv", true);
  return t;
}

double round3(double v) {
  return std::round(v * 1000.0) / 1000.0;
}

} // namespace

Spectrum illuminantA() {
  // CIE 15: S_A = 100 (560/l)^5 (exp(1.435e7 / (2848 * 560)) - 1) / (exp(1.435e7 / (2848 l)) - 1)
  std::vector<double> nm, v;
  // Computed over the whole traced range (a formula has no end to warn about).
  for (int l = static_cast<int>(kTraceMinNm); l <= static_cast<int>(kTraceMaxNm); ++l) {
    const double c2 = 1.435e7, t = 2848.0;
    nm.push_back(l);
    v.push_back(100.0 * std::pow(560.0 / l, 5.0) * std::expm1(c2 / (t * 560.0)) /
                std::expm1(c2 / (t * l)));
  }
  return Spectrum(TabulatedSpectrum{std::move(nm), std::move(v)});
}

double nominalDaylightCct(int hundredsOfKelvin) {
  return hundredsOfKelvin * 100.0 * 1.4388 / 1.4380;
}

Spectrum illuminantD(double cct) {
  if (!(cct >= 4000.0 && cct <= 25000.0))
    throw Error("daylight CCT must lie in 4000-25000 K, found " + std::to_string(cct));
  const double t = cct, t2 = t * t, t3 = t2 * t;
  const double xd = t <= 7000.0 ? -4.6070e9 / t3 + 2.9678e6 / t2 + 0.09911e3 / t + 0.244063
                                : -2.0064e9 / t3 + 1.9018e6 / t2 + 0.24748e3 / t + 0.237040;
  const double yd = -3.000 * xd * xd + 2.870 * xd - 0.275;
  const double m = 0.0241 + 0.2562 * xd - 0.7341 * yd;
  const double m1 = round3((-1.3515 - 1.7703 * xd + 5.9114 * yd) / m);
  const double m2 = round3((0.0300 - 31.4424 * xd + 30.0717 * yd) / m);
  std::vector<double> nm, v;
  for (const auto& row : daylightTable().rows) {
    nm.push_back(row.values[0]);
    v.push_back(row.values[1] + m1 * row.values[2] + m2 * row.values[3]);
  }
  return Spectrum(TabulatedSpectrum{std::move(nm), std::move(v)});
}

Spectrum illuminantF(int index) {
  if (index < 1 || index > 12)
    throw Error("fluorescent illuminants are F1-F12, found F" + std::to_string(index));
  std::vector<double> nm, v;
  for (const auto& row : fluorescentTable().rows) {
    nm.push_back(row.values[0]);
    v.push_back(row.values[static_cast<size_t>(index)]);
  }
  return Spectrum(TabulatedSpectrum{std::move(nm), std::move(v)});
}

Spectrum illuminantE() {
  return Spectrum(ConstantSpectrum{1.0});
}

Spectrum blackLight() {
  std::vector<double> nm, v;
  const GaussianSpectrum uv{368.0, 10.0, 1.0}, violet{404.7, 4.0, 0.3};
  for (int l = static_cast<int>(kTraceMinNm); l <= static_cast<int>(kTraceMaxNm); ++l) {
    nm.push_back(l);
    v.push_back(uv(l) + violet(l));
  }
  return Spectrum(TabulatedSpectrum{std::move(nm), std::move(v)});
}

double relativeLuminance(const Spectrum& s) {
  const auto& t = cieTables();
  double y = 0;
  for (int i = 0; i < kCieSamples; ++i) y += s(kCieMinNm + i) * t.yBar[i];
  return y / kCieYIntegral;
}

namespace {

double parseKelvin(const std::string& name, const std::string& text) {
  const double k = parseNumber(text, "emission '" + name + "'", "a temperature in kelvin");
  if (!(k >= 100.0 && k <= 1e6))
    throw Error("emission '" + name + "': expected a temperature in 100-1e6 K, found " + text);
  return k;
}

std::optional<Spectrum> unnormalisedEmission(const std::string& name) {
  if (name == "A") return illuminantA();
  if (name == "E") return illuminantE();
  if (name == "bl") return blackLight();
  if (name == "bba") return Spectrum(BlackbodySpectrum{2856});
  if (name == "bbd50") return Spectrum(BlackbodySpectrum{5003});
  if (name == "bbd55") return Spectrum(BlackbodySpectrum{5503});
  if (name == "bbd65") return Spectrum(BlackbodySpectrum{6504});
  if (name == "bbd75") return Spectrum(BlackbodySpectrum{7504});
  if (name.rfind("blackbody:", 0) == 0)
    return Spectrum(BlackbodySpectrum{parseKelvin(name, name.substr(10))});
  if (name.rfind("daylight:", 0) == 0) return illuminantD(parseKelvin(name, name.substr(9)));
  if (name.size() == 3 && name[0] == 'D' && std::isdigit(name[1]) && std::isdigit(name[2]))
    return illuminantD(nominalDaylightCct(std::stoi(name.substr(1))));
  if ((name.size() == 2 || name.size() == 3) && name[0] == 'F' && std::isdigit(name[1]) &&
      (name.size() == 2 || std::isdigit(name[2]))) {
    const int i = std::stoi(name.substr(1));
    if (i >= 1 && i <= 12) return illuminantF(i);
  }
  return std::nullopt;
}

} // namespace

std::optional<Spectrum> namedEmission(const std::string& name) {
  auto s = unnormalisedEmission(name);
  if (!s) return std::nullopt;
  if (name == "bl") {
    double radiance = 0; // 1 nm sum over 360-830 nm, against 471 for a flat 1
    for (int l = kCieMinNm; l <= kCieMaxNm; ++l) radiance += (*s)(l);
    return s->scaled(kCieSamples / radiance);
  }
  return s->scaled(1.0 / relativeLuminance(*s));
}

} // namespace nx
