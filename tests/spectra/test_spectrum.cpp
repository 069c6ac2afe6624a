#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "core/error.h"
#include "core/math_util.h"
#include "spectra/named_spectra.h"
#include "spectra/spectrum.h"
#include "spectra/spectrum_bounds.h"
#include "support/errors.h"

namespace nx {
namespace {

TEST(Spectrum, GaussianIsPeakNormalised) {
  const GaussianSpectrum g{545, 34, 1};
  EXPECT_DOUBLE_EQ(g(545), 1.0);
  EXPECT_NEAR(g(545 + 34), std::exp(-0.5), 1e-12);
  EXPECT_NEAR(g(545 - 68), std::exp(-2.0), 1e-12);
}

TEST(Spectrum, SkewCauchyIsADensityAndSkews) {
  for (double w : {0.0, 3.0, -10.0}) {
    const SkewCauchySpectrum f{500, 20, w};
    // Integral over the real line is 1/2 for every skew (the formula lacks the factor 2 of a
    // skew-symmetric density); integrate in the angle variable d = g tan(theta).
    double integral = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
      const double theta = -kPi / 2 + kPi * (i + 0.5) / n;
      const double d = 20 * std::tan(theta);
      integral += f(500 + d) * 20 / sqr(std::cos(theta)) * kPi / n;
    }
    EXPECT_NEAR(integral, 0.5, 1e-6) << w;
  }
  const SkewCauchySpectrum sym{500, 20, 0};
  EXPECT_NEAR(sym(480), sym(520), 1e-15);
  EXPECT_NEAR(sym(500), 0.5 / (kPi * 20), 1e-15); // g / (pi g^2) * 1/2
  const SkewCauchySpectrum pos{500, 20, 10};
  EXPECT_GT(pos(530), pos(470)); // positive skew: the tail runs to long wavelengths
  // Closed form at d = g: g / (pi 2 g^2) (atan(w) / pi + 1/2).
  EXPECT_NEAR(pos(520), 1.0 / (kPi * 40) * (std::atan(10.0) / kPi + 0.5), 1e-15);
}

TEST(Spectrum, TabulatedInterpolatesAndIsZeroOutside) {
  const Spectrum t(makeTabulated({400, 500, 600}, {1, 3, 2}, "test"));
  EXPECT_DOUBLE_EQ(t(400), 1);
  EXPECT_DOUBLE_EQ(t(450), 2);
  EXPECT_DOUBLE_EQ(t(575), 2.25);
  EXPECT_DOUBLE_EQ(t(600), 2);
  EXPECT_DOUBLE_EQ(t(399.9), 0);
  EXPECT_DOUBLE_EQ(t(600.1), 0);
  EXPECT_DOUBLE_EQ(t.scaled(2)(450), 4);
}

// A pseudo-random number in [0, 1) from a running state (fixed sequence).
double nextUnit(uint32_t& state) {
  state = state * 1664525u + 1013904223u;
  return static_cast<double>(state >> 8) / static_cast<double>(1u << 24);
}

// The indexed copy of t (buildIndex) gives the binary search's value bit for bit at knots,
// next to knots, between them, at and beyond the ends and at NaN.
void expectIndexEqualsSearch(const TabulatedSpectrum& t, const TabulatedSpectrum& fast,
                             uint32_t& state, const std::string& what) {
  const double range = t.nm.back() - t.nm.front();
  std::vector<double> xs{t.nm.front() - 1, t.nm.back() + 1, t.nm.front(), t.nm.back(), NAN};
  for (double k : t.nm)
    for (double x : {k, std::nextafter(k, 0.0), std::nextafter(k, 1e9)}) xs.push_back(x);
  for (int i = 0; i < 2000; ++i)
    xs.push_back(t.nm.front() - 0.1 * range + 1.2 * range * nextUnit(state));
  for (double x : xs) {
    const double a = t(x), b = fast(x);
    if (std::isnan(x))
      EXPECT_EQ(std::isnan(a), std::isnan(b)) << what;
    else
      ASSERT_EQ(a, b) << what << " at " << x;
  }
}

// The grid index of evenly spaced tables finds the interval the binary search finds, for exact
// and jittered grids, with and without held ends.
TEST(Spectrum, UniformGridIndexEqualsTheSearch) {
  uint32_t state = 12345;
  int indexed = 0;
  for (int table = 0; table < 40; ++table) {
    const double step = table % 4 == 0 ? 1.0 : table % 4 == 1 ? 5.0 : 0.1 + 20 * nextUnit(state);
    const double jitter = table % 3 == 0 ? 0.0 : 0.2 * step; // within the half-step bound
    const size_t n = 3 + static_cast<size_t>(nextUnit(state) * 400);
    TabulatedSpectrum t;
    for (size_t i = 0; i < n; ++i) {
      t.nm.push_back(350 + step * static_cast<double>(i) +
                     (i > 0 ? jitter * (2 * nextUnit(state) - 1) : 0));
      t.value.push_back(nextUnit(state));
    }
    t.holdEnds = table % 2 == 0;
    TabulatedSpectrum fast = t;
    fast.buildIndex();
    ASSERT_GT(fast.invStep, 0) << "table " << table;
    EXPECT_TRUE(fast.cellFirst.empty());
    ++indexed;
    expectIndexEqualsSearch(t, fast, state, "table " + std::to_string(table));
  }
  EXPECT_EQ(indexed, 40);
  // And the renderer's copy of a tabulated spectrum is indexed.
  const Spectrum r = forRendering(Spectrum(TabulatedSpectrum{{400, 410, 420}, {1, 2, 3}}, 2));
  EXPECT_GT(std::get<TabulatedSpectrum>(r.kind()).invStep, 0);
  EXPECT_DOUBLE_EQ(r(415), 5.0);
}

// Unevenly spaced tables (an LED's CSV at 380, 430, 450, ... nm; gaps from 0.01 to 50 nm;
// clusters of close wavelengths in wide gaps; one gap far below the range / kIndexCells) are
// indexed by cells and give the search's values bit for bit; the renderer's copy is indexed.
TEST(Spectrum, UnevenTableIndexEqualsTheSearch) {
  uint32_t state = 777;
  const std::vector<std::vector<double>> grids = {
      {380, 430, 450, 455, 460, 470, 520, 780},
      {400, 401, 410, 411},
  };
  std::vector<std::vector<double>> all = grids;
  for (int table = 0; table < 30; ++table) {
    std::vector<double> nm{300 + 100 * nextUnit(state)};
    const size_t n = 3 + static_cast<size_t>(nextUnit(state) * 300);
    for (size_t i = 1; i < n; ++i) // log-uniform gaps from 0.01 to 50 nm
      nm.push_back(nm.back() + 0.01 * std::pow(5000.0, nextUnit(state)));
    if (table % 5 == 0) nm.insert(nm.begin() + 1, nm[0] + 1e-6); // a gap of 1e-6 nm
    all.push_back(nm);
  }
  for (size_t g = 0; g < all.size(); ++g) {
    TabulatedSpectrum t;
    t.nm = all[g];
    for (size_t i = 0; i < t.nm.size(); ++i) t.value.push_back(nextUnit(state));
    t.holdEnds = g % 2 == 0;
    TabulatedSpectrum fast = t;
    fast.buildIndex();
    EXPECT_EQ(fast.invStep, 0) << g;
    ASSERT_FALSE(fast.cellFirst.empty()) << g;
    EXPECT_LE(fast.cellFirst.size(), TabulatedSpectrum::kIndexCells);
    expectIndexEqualsSearch(t, fast, state, "uneven table " + std::to_string(g));
  }
  const Spectrum r = forRendering(Spectrum(TabulatedSpectrum{{400, 401, 410, 411}, {1, 2, 3, 4}}));
  EXPECT_FALSE(std::get<TabulatedSpectrum>(r.kind()).cellFirst.empty());
  EXPECT_DOUBLE_EQ(r(405.5), 2.5);
}

TEST(Spectrum, TabulatedRejectsBadPairs) {
  EXPECT_THROW(makeTabulated({400}, {1}, "x"), Error);
  EXPECT_THROW(makeTabulated({400, 400}, {1, 2}, "x"), Error);
  EXPECT_THROW(makeTabulated({500, 400}, {1, 2}, "x"), Error);
  EXPECT_THROW(makeTabulated({400, 500}, {1}, "x"), Error);
  EXPECT_THROW(makeTabulated({400, NAN}, {1, 2}, "x"), Error);
}

std::string writeTemp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

std::string csvError(const std::string& text) {
  const std::string path = writeTemp("spectrum.csv", text);
  const std::string message = test::errorMessage([&] { readSpectrumCsv(path); });
  return message == "no error" ? message : message.substr(path.size());
}

TEST(Spectrum, CsvFile) {
  const std::string path =
      writeTemp("ok.csv", "wavelength,reflectance\n400,0.1\n500,0.5\n700,0.9\n");
  const Spectrum s(readSpectrumCsv(path));
  EXPECT_DOUBLE_EQ(s(450), 0.3);
  EXPECT_DOUBLE_EQ(s(600), 0.7);
  EXPECT_EQ(csvError("400,0.1\n500,0.5,3\n"),
            ":2: expected 2 columns (wavelength, value), found 3");
  EXPECT_EQ(csvError("400,0.1\n390,0.5\n"),
            ":2: expected wavelengths in increasing order, found 390.000000 after 400.000000");
  EXPECT_EQ(csvError("400,0.1\n500,x\n"), ":2: expected a number, found 'x'");
  EXPECT_EQ(csvError("400,0.1\n"), ": expected at least two (wavelength, value) pairs, found 1");
}

TEST(Spectrum, DispatchOverLanesMatchesPointwise) {
  const Spectrum s(SkewCauchySpectrum{450, 15, -4}, 3.0);
  std::array<float, 3> nm{420.f, 450.f, 470.f};
  std::array<float, 3> out{};
  s.evaluate(nm, out);
  for (int i = 0; i < 3; ++i) EXPECT_FLOAT_EQ(out[i], static_cast<float>(s(nm[i])));
}

TEST(NamedSpectra, NiixtracerReflectances) {
  const std::pair<const char*, double> peaks[] = {{"red", 680},   {"orange", 620}, {"yellow", 600},
                                                  {"green", 545}, {"blue", 460},   {"purple", 420},
                                                  {"uv", 360}};
  for (auto [name, peak] : peaks) {
    const Spectrum s = *namedReflectance(name);
    EXPECT_DOUBLE_EQ(s(peak), 1.0) << name;
    EXPECT_NEAR(s(peak + 34), std::exp(-0.5), 1e-12) << name;
  }
  EXPECT_DOUBLE_EQ((*namedReflectance("const"))(500), 1.0);
  EXPECT_DOUBLE_EQ((*namedReflectance("null"))(500), 0.0);
  EXPECT_DOUBLE_EQ((*namedReflectance("gray"))(500), 0.5);
  EXPECT_FALSE(namedReflectance("grey").has_value());
  EXPECT_EQ(*namedAbsorptionPeak("uv"), 370.0);
  EXPECT_EQ(*namedAbsorptionPeak("blue"), 460.0);
  EXPECT_FALSE(namedAbsorptionPeak("gray").has_value());
}

// The exact extremes over an interval agree with a brute-force scan every 0.001 nm: nothing
// the scan finds lies outside them, they are attained where they say, and a spike between
// whole nanometres (which a 1 nm scan misses) is found.
TEST(SpectrumExtremes, MatchBruteForceForEveryKind) {
  const std::vector<std::pair<const char*, Spectrum>> cases{
      {"constant scaled negative", Spectrum(ConstantSpectrum{0.3}, -2.0)},
      {"tabulated spike",
       Spectrum(makeTabulated({350, 500, 500.4, 500.8, 900}, {0.2, 0.5, 1.5, 0.5, 0.1}, "t"))},
      {"tabulated inside the range (zero outside)",
       Spectrum(makeTabulated({400, 700}, {0.3, 0.6}, "t"))},
      {"dense gaussian", forRendering(Spectrum(GaussianSpectrum{612.3, 7, 2}))},
      {"gaussian", Spectrum(GaussianSpectrum{612.3, 7, 2})},
      {"gaussian outside", Spectrum(GaussianSpectrum{1200, 40, 1})},
      {"blackbody 3000 K", Spectrum(BlackbodySpectrum{3000})},
      {"blackbody 6500 K", Spectrum(BlackbodySpectrum{6500})},
      {"sigmoid with a vertex inside", Spectrum(SigmoidPolynomialSpectrum{40, -30, 2})},
      {"skew-cauchy", Spectrum(SkewCauchySpectrum{520, 3, 6}, 5.0)},
  };
  for (const auto& [what, sp] : cases) {
    const double lo = 300, hi = 1000;
    const SpectrumExtremes e = spectrumExtremes(sp, lo, hi);
    ASSERT_TRUE(std::isfinite(e.min) && std::isfinite(e.max)) << what;
    double scanMin = INFINITY, scanMax = -INFINITY;
    for (double nm = lo; nm <= hi; nm += 0.001) {
      scanMin = std::min(scanMin, sp(nm));
      scanMax = std::max(scanMax, sp(nm));
    }
    const double tol = 1e-9 * std::max(1.0, std::abs(e.max));
    EXPECT_LE(e.min, scanMin + tol) << what;
    EXPECT_GE(e.max, scanMax - tol) << what;
    EXPECT_NEAR(sp(e.minNm), e.min, tol) << what;
    EXPECT_NEAR(sp(e.maxNm), e.max, tol) << what;
    // Tight: the scan comes within its resolution of the extremes.
    EXPECT_NEAR(scanMax, e.max, 1e-4 * std::max(1.0, std::abs(e.max))) << what;
  }
  const SpectrumExtremes spike = spectrumExtremes(cases[1].second, 300, 1000);
  EXPECT_EQ(spike.max, 1.5);
  EXPECT_EQ(spike.maxNm, 500.4);
  EXPECT_EQ(spike.min, 0.0); // zero beyond the table's last wavelength
  const SpectrumExtremes inner = spectrumExtremes(cases[2].second, 300, 1000);
  EXPECT_EQ(inner.min, 0.0);
  EXPECT_EQ(inner.max, 0.6);
  // A table holding its ends is never 0 beyond them (a conductor's eta given from 400 nm).
  TabulatedSpectrum held{{400, 800}, {0.2, 0.3}};
  held.holdEnds = true;
  const SpectrumExtremes h = spectrumExtremes(Spectrum(held), 300, 1000);
  EXPECT_EQ(h.min, 0.2);
  EXPECT_EQ(h.max, 0.3);
}

} // namespace
} // namespace nx

namespace nx {
namespace {

// A multi-column spectral file (e.g. a chart's patches): column="name" takes that column; a
// wrong name lists the columns there are; without a column the message says how to choose.
TEST(Spectrum, CsvColumnSelection) {
  const std::string csv = "wavelength,dark_skin,light_skin\n400,0.05,0.18\n500,0.06,0.3\n";
  const TabulatedSpectrum light = parseSpectrumCsv(csv, "cc.csv", "light_skin");
  EXPECT_DOUBLE_EQ(light(450), 0.24);
  EXPECT_DOUBLE_EQ(parseSpectrumCsv(csv, "cc.csv", "dark_skin")(500), 0.06);
  EXPECT_EQ(test::errorMessage([&] { parseSpectrumCsv(csv, "cc.csv", "cyan"); }),
            "cc.csv:1: expected a value column named 'cyan', found the columns wavelength, "
            "dark_skin, light_skin");
  EXPECT_EQ(test::errorMessage([&] { parseSpectrumCsv(csv, "cc.csv", "wavelength"); }),
            "cc.csv:1: expected a value column named 'wavelength', found the columns wavelength, "
            "dark_skin, light_skin");
  EXPECT_EQ(test::errorMessage([&] { parseSpectrumCsv(csv, "cc.csv"); }),
            "cc.csv:2: expected 2 columns (wavelength, value), found 3 (choose one with "
            "column=\"name\": wavelength, dark_skin, light_skin)");
  EXPECT_EQ(test::errorMessage([&] { parseSpectrumCsv("400,1\n500,2\n", "n.csv", "a"); }),
            "n.csv:1: expected a header naming the columns (to find column 'a'), found none");
}

// Semicolons with decimal commas (a spreadsheet in a decimal-comma locale) are named as such;
// semicolons alone are a separator like commas.
TEST(Spectrum, DecimalCommasAreNamed) {
  EXPECT_EQ(test::errorMessage([] { parseSpectrumCsv("nm;value\n400;0,5\n", "de.csv"); }),
            "de.csv:2: expected numbers with decimal points, found '400;0,5' (semicolons and "
            "decimal commas, as a spreadsheet in a decimal-comma locale writes; export with "
            "decimal points, e.g. 400,0.5 or 400;0.5)");
  EXPECT_DOUBLE_EQ(parseSpectrumCsv("400;0.5\n500;0.7\n", "s.csv")(500), 0.7);
}

} // namespace
} // namespace nx
