#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "spectra/colour.h"
#include "spectra/sigmoid_table.h"
#include "spectra/spectrum.h"

namespace nx {
namespace {

const SigmoidTable::ForEach serial = [](int count, const std::function<void(int)>& body) {
  for (int i = 0; i < count; ++i) body(i);
};

TEST(SigmoidFit, GreyCoefficientsGiveTheConstant) {
  for (double z : {0.01, 0.18, 0.5, 0.9, 0.999}) {
    const SigmoidCoefficients c = greySigmoidCoefficients(z);
    const SigmoidPolynomialSpectrum s{c[0], c[1], c[2]};
    EXPECT_NEAR(s(400), z, 1e-12);
    EXPECT_NEAR(s(700), z, 1e-12);
  }
}

// The analytic Jacobian drives Levenberg-Marquardt to the colour from a nearby start.
TEST(SigmoidFit, ConvergesFromANearbyColour) {
  const Rgb target{0.35, 0.2, 0.1};
  const SigmoidCoefficients c = fitSigmoidCoefficients(target, greySigmoidCoefficients(0.2));
  EXPECT_LT(sigmoidFitDeltaE(c, target), 1e-3);
  const Rgb far{0.05, 0.6, 0.1};
  const SigmoidCoefficients d =
      fitSigmoidCoefficientsFrom(far, {0.5, 0.5, 0.5}, greySigmoidCoefficients(0.5), 8);
  EXPECT_LT(sigmoidFitDeltaE(d, far), 1e-3);
}

// A small table fitted here reproduces the colours of its grid through lookup: with the
// largest channel's value z at the table's z positions and the other two channels at z x and
// z y for x, y on the grid (the header's parameterisation, written out per largest channel
// rather than by the table's own index arithmetic), the looked-up spectrum has that colour.
TEST(SigmoidTable, LookupsReproduceTheGridColours) {
  const int res = 6;
  const std::vector<float> z = SigmoidTable::zPositions(res);
  const SigmoidTable table(res, z, SigmoidTable::fit(res, serial));
  double worst = 0, between = 0;
  for (int k = 1; k < res; ++k)
    for (int j = 0; j < res; ++j)
      for (int i = 0; i < res; ++i) {
        const double v = z[static_cast<size_t>(k)], x = v * i / (res - 1.0),
                     y = v * j / (res - 1.0);
        // Red, green, then blue the largest channel (ties excepted: x, y < 1 there).
        for (const Rgb c : {Rgb{v, x, y}, Rgb{y, v, x}, Rgb{x, y, v}}) {
          if (i == res - 1 || j == res - 1) continue;
          worst = std::max(worst, sigmoidFitDeltaE(table.lookup(c), c));
        }
        if (i + 1 < res && j + 1 < res) {
          const double xm = v * (i + 0.5) / (res - 1.0), ym = v * (j + 0.5) / (res - 1.0);
          const Rgb mid{v, xm, ym};
          between = std::max(between, sigmoidFitDeltaE(table.lookup(mid), mid));
        }
      }
  EXPECT_LT(worst, 0.02); // float rounding of the fitted coefficients
  // Between the points a coarse 6^3 grid interpolates: there the colour is off (the check has
  // power: it would see a lookup that returned other entries than the grid's).
  EXPECT_GT(between, 10 * worst);
}

TEST(SigmoidTable, BinaryFormRoundTripsAndRejectsOtherBytes) {
  const int res = 3;
  const SigmoidTable table(res, SigmoidTable::zPositions(res), SigmoidTable::fit(res, serial));
  const std::string bytes = table.toBytes();
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
  const SigmoidTable back = SigmoidTable::fromBytes(p, bytes.size());
  const Rgb c{0.3, 0.6, 0.2};
  EXPECT_EQ(back.lookup(c), table.lookup(c));
  EXPECT_THROW(SigmoidTable::fromBytes(p, bytes.size() - 4), std::invalid_argument);
  EXPECT_THROW(SigmoidTable::fromBytes(p, 6), std::invalid_argument);
  std::string wrong = bytes;
  wrong[0] = 'X';
  EXPECT_THROW(
      SigmoidTable::fromBytes(reinterpret_cast<const unsigned char*>(wrong.data()), wrong.size()),
      std::invalid_argument);
}

// The built-in table on a grid of encoded sRGB values finer than its own: interpolation
// error well below a just-noticeable difference.
TEST(SigmoidTable, BuiltInTableRoundTripsAFineGrid) {
  const SigmoidTable& table = srgbSigmoidTable();
  const int n = 20;
  double worst = 0, sum = 0;
  int count = 0;
  for (int r = 0; r <= n; ++r)
    for (int g = 0; g <= n; ++g)
      for (int b = 0; b <= n; ++b) {
        if (r == g && g == b && (r == 0 || r == n)) continue; // constant spectra, not looked up
        const Rgb c{srgbDecode(r / double(n)), srgbDecode(g / double(n)),
                    srgbDecode(b / double(n))};
        const double de = sigmoidFitDeltaE(table.lookup(c), c);
        worst = std::max(worst, de);
        sum += de;
        ++count;
      }
  std::printf("built-in table (%d^3): mean Delta E 2000 %.4f, worst %.4f\n", table.resolution(),
              sum / count, worst);
  EXPECT_LT(worst, 1.0);
  EXPECT_LT(sum / count, 0.1);
}

// Where the largest channel changes (r = g here) the two sub-tables meet: colours either
// side of the boundary get nearly the same spectrum.
TEST(SigmoidTable, SubTablesAgreeWhereTheLargestChannelChanges) {
  const SigmoidTable& table = srgbSigmoidTable();
  for (const Rgb base : {Rgb{0.5, 0.5, 0.2}, Rgb{0.9, 0.2, 0.9}, Rgb{0.05, 0.3, 0.3}}) {
    const double e = 1e-7;
    Rgb a = base, b = base;
    if (base.r == base.g) a.r += e, b.g += e;
    if (base.r == base.b) a.r += e, b.b += e;
    if (base.g == base.b) a.g += e, b.b += e;
    const SigmoidCoefficients ca = table.lookup(a), cb = table.lookup(b);
    const SigmoidPolynomialSpectrum sa{ca[0], ca[1], ca[2]}, sb{cb[0], cb[1], cb[2]};
    for (double nm = 380; nm <= 780; nm += 20) EXPECT_NEAR(sa(nm), sb(nm), 2e-3) << nm;
  }
}

} // namespace
} // namespace nx
