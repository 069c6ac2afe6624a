#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <random>

#include "core/error.h"
#include "spectra/reradiation_matrix.h"
#include "spectra/spectrum.h"
#include "support/errors.h"
#include "support/statistics.h"

namespace nx {
namespace {

using RM = ReradiationMatrix;

FluorescenceModel model(double peak, double stokes, double yield = 1, double width = 20,
                        double skew = 10, double aMax = 1) {
  return {peak, stokes, width, skew, yield, aMax};
}

TEST(ReradiationMatrix, Grid) {
  // The grid covers the whole traced range, 300-1100 nm.
  EXPECT_EQ(RM::kBins, 160);
  EXPECT_EQ(RM::binOf(300), 0);
  EXPECT_EQ(RM::binOf(304.99), 0);
  EXPECT_EQ(RM::binOf(305), 1);
  EXPECT_EQ(RM::binOf(1099.99), 159);
  EXPECT_EQ(RM::binOf(1100), -1);
  EXPECT_EQ(RM::binOf(299.9), -1);
  EXPECT_DOUBLE_EQ(RM::centre(0), 302.5);
  EXPECT_DOUBLE_EQ(RM::kMinNm, kTraceMinNm);
  EXPECT_DOUBLE_EQ(RM::kMinNm + RM::kBins * RM::kBinNm, kTraceMaxNm);
}

// M[i][o] = a_i Q e_o l_i / l_o above the diagonal, 0 on and below it; a peaks at a_max;
// the emission distribution e sums to 1.
TEST(ReradiationMatrix, ModelEntries) {
  const FluorescenceModel p = model(460, 120, 0.8, 25, 6, 0.7);
  const RM m = RM::fromModel(p);
  double aMax = 0;
  for (int i = 0; i < RM::kBins; ++i) aMax = std::max(aMax, m.absorptance(i));
  EXPECT_NEAR(aMax, 0.7, 1e-12);
  const SkewCauchySpectrum abs{460, 25, -6}, em{580, 25, 6};
  double maxAbs = 0, sumEm = 0;
  for (int i = 0; i < RM::kBins; ++i)
    maxAbs = std::max(maxAbs, abs(RM::centre(i))), sumEm += em(RM::centre(i));
  for (int i = 0; i < RM::kBins; i += 7) {
    EXPECT_NEAR(m.absorptance(i), 0.7 * abs(RM::centre(i)) / maxAbs, 1e-12);
    for (int o = 0; o < RM::kBins; o += 3) {
      const double expected =
          o > i ? m.absorptance(i) * 0.8 * em(RM::centre(o)) / sumEm * RM::centre(i) / RM::centre(o)
                : 0.0;
      EXPECT_NEAR(m(i, o), expected, 1e-15) << i << " " << o;
    }
  }
  // The l_i / l_o energy factor between two entries of a row.
  const int i = RM::binOf(400), o1 = RM::binOf(560), o2 = RM::binOf(620);
  EXPECT_NEAR(m(i, o1) / m(i, o2),
              em(RM::centre(o1)) / em(RM::centre(o2)) * RM::centre(o2) / RM::centre(o1), 1e-12);
}

// Conservation: every row re-radiates at most what it absorbs (times Q), and a row whose
// emission lies entirely above it re-radiates a_i Q <l_i / l_o>.
TEST(ReradiationMatrix, RowAndColumnSums) {
  const RM m = RM::fromModel(model(420, 150, 0.9));
  for (int i = 0; i < RM::kBins; ++i) {
    double row = 0, photons = 0;
    for (int o = 0; o < RM::kBins; ++o) {
      row += m(i, o);
      photons += m(i, o) * RM::centre(o) / RM::centre(i);
    }
    EXPECT_LE(row, m.absorptance(i) * 0.9 + 1e-15);
    EXPECT_LE(photons, m.absorptance(i) * 0.9 + 1e-12); // photon yield <= Q
  }
  // Excitation at 362.5 nm: almost all of the emission (around 570 nm) lies above it.
  double photons = 0;
  for (int o = 0; o < RM::kBins; ++o) photons += m(0, o) * RM::centre(o) / RM::centre(0);
  EXPECT_NEAR(photons, m.absorptance(0) * 0.9, 0.02 * m.absorptance(0));
  for (int o = 0; o < RM::kBins; ++o) {
    double c = 0;
    for (int i = 0; i < RM::kBins; ++i) c += m(i, o);
    EXPECT_NEAR(m.columnSum(o), c, 1e-15);
  }
}

// Counts an excitation event drawn for a lane at nm (bin o): the elastic event (l == nm) in
// obs[kBins], a fluorescent one in its bin, which must lie below o.
void countExcitationEvent(std::vector<double>& obs, double l, double nm, int o) {
  if (l == nm) {
    obs[RM::kBins] += 1;
    return;
  }
  ASSERT_LT(RM::binOf(l), o);
  obs[static_cast<size_t>(RM::binOf(l))] += 1;
}

// Stratified u over the outcomes of a lane at nm: elastic with probability D / (D + c), bin i
// with probability M[i][o] / (D + c); the inverse CDF keeps the counts within one sample of
// their expectation, and never picks an empty bin.
void expectExcitationSamplingMatches(const RM& m, double nm) {
  const double rho = 0.6;
  const int o = RM::binOf(nm);
  const double d = m.elastic(o, rho), c = m.columnSum(o);
  std::vector<double> obs(RM::kBins + 1, 0), exp(RM::kBins + 1, 0);
  const int n = 200000;
  for (int k = 0; k < n; ++k) {
    float w = 1;
    const double u = (k + 0.5) / n, v = std::fmod(k * 0.618033988749895, 1.0);
    const double l = m.sampleExcitation(static_cast<float>(nm), static_cast<float>(rho),
                                        static_cast<float>(u), static_cast<float>(v), w);
    EXPECT_NEAR(w, d + c, 1e-6);
    countExcitationEvent(obs, l, nm, o);
  }
  for (int i = 0; i < RM::kBins; ++i) exp[i] = n * m(i, o) / (d + c);
  exp[RM::kBins] = n * d / (d + c);
  // Stratified u: the counts match the probabilities to within one sample per outcome.
  for (int i = 0; i <= RM::kBins; ++i) EXPECT_NEAR(obs[i], exp[i], 1.5) << nm << " nm, bin " << i;
}

TEST(ReradiationMatrix, ExcitationSamplingMatchesTheMatrix) {
  const RM m = RM::fromModel(model(430, 90, 1));
  const RM measured = RM::fromMeasured(parseMeasuredMatrixCsv(m.toCsv(), "m.csv"));
  for (double nm : {372.5, 532.0, 601.0, 829.0, 1012.0}) {
    expectExcitationSamplingMatches(m, nm);
    expectExcitationSamplingMatches(measured, nm);
  }
  float w = 1;
  EXPECT_EQ(m.sampleExcitation(1100, 0.6f, 0.5f, 0.5f, w), 1100); // outside the grid: reflector
  EXPECT_FLOAT_EQ(w, 0.6f);
}

// The same for a dye at relative concentration k (sampleExcitationScaled): elastic with
// probability (1 - k a_o) rho / total, bin i with probability k M[i][o] / total.
TEST(ReradiationMatrix, ScaledExcitationSamplingMatchesTheScaledMatrix) {
  const RM m = RM::fromModel(model(430, 90, 1));
  const double rho = 0.6;
  for (double k : {0.0, 0.3, 1.0})
    for (double nm : {532.0, 601.0}) {
      const int o = RM::binOf(nm);
      const double d = m.elastic(o, rho, k), c = k * m.columnSum(o);
      EXPECT_NEAR(d, (1 - k * m.absorptance(o)) * rho, 1e-12);
      std::vector<double> obs(RM::kBins + 1, 0);
      const int n = 200000;
      for (int j = 0; j < n; ++j) {
        float w = 1;
        const double u = (j + 0.5) / n, v = std::fmod(j * 0.618033988749895, 1.0);
        const double l = m.sampleExcitationScaled(static_cast<float>(nm), static_cast<float>(rho),
                                                  static_cast<float>(k), static_cast<float>(u),
                                                  static_cast<float>(v), w);
        EXPECT_NEAR(w, d + c, 1e-6);
        countExcitationEvent(obs, l, nm, o);
      }
      for (int i = 0; i < RM::kBins; ++i)
        EXPECT_NEAR(obs[i], n * k * m(i, o) / (d + c), 1.5) << k << ", " << nm << " nm, bin " << i;
      EXPECT_NEAR(obs[RM::kBins], n * d / (d + c), 1.5) << k << ", " << nm << " nm, elastic";
    }
}

TEST(ReradiationMatrix, CsvRoundTrip) {
  const RM m = RM::fromModel(model(460, 220, 0.75));
  const std::string path = ::testing::TempDir() + "matrix.csv";
  std::ofstream(path) << m.toCsv();
  const RM back = RM::fromMeasured(readMeasuredMatrixCsv(path));
  EXPECT_TRUE(back.measured());
  for (int i = 0; i < RM::kBins; ++i) {
    EXPECT_NEAR(back.elastic(i, 0.3), 1 - m.absorptance(i), 1e-12); // measured D ignores rho
    for (int o = 0; o < RM::kBins; ++o) EXPECT_NEAR(back(i, o), m(i, o), 1e-12) << i << " " << o;
  }
}

std::string csvError(const std::string& text) {
  const std::string path = ::testing::TempDir() + "bad_matrix.csv";
  std::ofstream(path) << text;
  const std::string message =
      test::errorMessage([&] { RM::fromMeasured(readMeasuredMatrixCsv(path)); });
  return message == "no error" ? message : message.substr(path.size());
}

TEST(ReradiationMatrix, MalformedCsvIsRefusedWithFileAndLine) {
  EXPECT_EQ(csvError("ex,400,500\n350,0.1\n"),
            ":2: expected 3 cells (excitation wavelength and 2 values), found 2");
  EXPECT_EQ(csvError("ex,500,400\n350,0.1,0.1\n"),
            ":1: expected increasing emission wavelengths, found 400.000000 after 500.000000");
  EXPECT_EQ(csvError("ex,400,500\n450,0.1,0.1\n350,0.1,0.1\n"),
            ":3: expected increasing excitation wavelengths, found 350.000000 after 450.000000");
  EXPECT_EQ(csvError("ex,400,500\n350,0.1,1.5\n450,0,0\n"),
            ":2: expected matrix values in [0, 1], found 1.500000");
  EXPECT_EQ(csvError("ex,400,500\n350,0.1,x\n"), ":2: expected a number, found 'x'");
  EXPECT_EQ(csvError("ex,4o0,500\n350,0.1,0.2\n"),
            ":1: expected an emission wavelength, found '4o0'");
  EXPECT_EQ(csvError("ex,400,500\n350,0.1,0.2\n"), ": expected at least two excitation rows");
  EXPECT_EQ(csvError("ex,400,410,420\n400,0.1,1,1\n410,0,0.1,1\n").substr(0, 60),
            ": expected a matrix whose reflectance (diagonal) plus re-rad");
  // A diagonal of zeros is no diagonal: the elastic part is the surface's reflectance.
  EXPECT_NE(csvError("ex,400,410,420\n400,0,1,1\n410,0,0,1\n")
                .find("(the surface's <reflectance>: the matrix's diagonal is all zero)"),
            std::string::npos);
  // Each part within [0, 1], their sum above 1: a diagonal of 0.9 and 0.79 re-radiated.
  EXPECT_EQ(csvError("ex,400,500,600\n400,0.9,0.79,0\n500,0,0.9,0.79\n600,0,0,0.9\n").substr(0, 72),
            ": expected a matrix whose reflectance (diagonal) plus re-radiated energy");
}

} // namespace
} // namespace nx

namespace nx {
namespace {

using RM = ReradiationMatrix;

// A guide from a spectrum given per nm (bin means by the midpoint rule, as the light sampler).
ExcitationGuide guideOf(const std::function<double(double)>& s) {
  ExcitationGuide g;
  g.lo = RM::kBins, g.hi = 0;
  for (int i = 0; i < RM::kBins; ++i) {
    double sum = 0;
    for (int j = 0; j < 20; ++j) sum += s(RM::kMinNm + (i + (j + 0.5) / 20) * RM::kBinNm);
    g.mean[static_cast<size_t>(i)] = static_cast<float>(sum / 20);
    if (sum > 0) g.lo = std::min(g.lo, i), g.hi = i + 1;
  }
  return g;
}

// A royal-blue LED: a Gaussian at 450 nm, FWHM 20 nm, zero beyond 3 FWHM.
double royalBlue(double nm) {
  const double x = (nm - 450) / (20 / 2.3548);
  return std::abs(nm - 450) < 60 ? std::exp(-0.5 * x * x) : 0.0;
}

// The guided event of guidedExcitation is drawn with probability v(e) g(e) / Z (v = D for the
// elastic event, k M[i][o] for bin i): stratified u gives the counts to within a sample and a
// seeded random u passes a chi-square test, for the model and a measured matrix, at k = 1 and
// a concentration k = 0.4.
TEST(ReradiationMatrix, GuidedExcitationSamplingMatchesColumnTimesGuide) {
  const RM model = RM::fromModel({440, 80, 20, 10, 0.9, 0.8});
  const RM measured = RM::fromMeasured(parseMeasuredMatrixCsv(model.toCsv(), "m.csv"));
  const ExcitationGuide led = guideOf(royalBlue);
  const double rho = 0.5;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (const RM* m : {&model, &measured})
    for (double k : {1.0, 0.4})
      for (double nm : {452.0, 530.0, 601.0}) {
        if (m->measured() && k != 1) continue; // maps are refused with measured matrices
        const int o = RM::binOf(nm);
        const double d = k == 1 ? m->elastic(o, rho) : m->elastic(o, rho, k);
        std::vector<double> p(RM::kBins + 1, 0);
        p[RM::kBins] = d * led.mean[static_cast<size_t>(o)];
        for (int i = 0; i < o; ++i)
          p[static_cast<size_t>(i)] = k * (*m)(i, o) * led.mean[static_cast<size_t>(i)];
        double z = 0;
        for (double x : p) z += x;
        ASSERT_GT(z, 0);
        for (int pass = 0; pass < 2; ++pass) {
          const int n = 200000;
          std::vector<double> obs(RM::kBins + 1, 0), exp(RM::kBins + 1);
          for (int j = 0; j < n; ++j) {
            const float u = pass == 0 ? static_cast<float>((j + 0.5) / n) : uniform(rng);
            const GuidedExcitation e =
                m->guidedExcitation(static_cast<float>(nm), static_cast<float>(nm),
                                    static_cast<float>(rho), static_cast<float>(k), led, u, 0.5f);
            countExcitationEvent(obs, e.nm[1], static_cast<float>(nm), o);
          }
          for (size_t i = 0; i < p.size(); ++i) exp[i] = n * p[i] / z;
          if (pass == 0) {
            for (size_t i = 0; i < p.size(); ++i)
              EXPECT_NEAR(obs[i], exp[i], 2.0) << nm << " nm, k " << k << ", event " << i;
          } else {
            const auto [stat, dof] = test::chiSquare(obs, exp);
            EXPECT_LT(test::chiSquareZ(stat, std::max(dof, 1)), 4.0) << nm << " nm, k " << k;
          }
        }
      }
}

// The lights the MIS tests check the guided excitation's expectation for: the guide's own LED,
// a broadband light it does not describe, and a band where the LED is dark.
std::vector<std::function<double(double)>> misTestLights() {
  return {royalBlue, [](double nm) { return 0.2 + nm / 1000; },
          [](double nm) { return nm > 500 && nm < 520 ? 1.0 : 0.0; }};
}

// Calls f(light index, its guide, nm, bin o, elastic D, column total) for each light of
// misTestLights at three wavelengths.
template <class F>
void forEachMisCase(const RM& m, double rho, F&& f) {
  const std::vector<std::function<double(double)>> lights = misTestLights();
  for (size_t li = 0; li < lights.size(); ++li) {
    const ExcitationGuide lbar = guideOf(lights[li]);
    for (double nm : {452.0, 530.0, 601.0}) {
      const int o = RM::binOf(nm);
      const double d = m.elastic(o, rho);
      f(li, lbar, nm, o, d, d + m.columnSum(o));
    }
  }
}

// The multi-sample MIS combination is unbiased for any light, not only the guide's. Each event
// e is drawn by the column with p_c = v(e) / (D + c) (tested above) and by the guide with
// p_g = v(e) g(e) / Z (tested above); its weight as the column's event is read back from
// guidedExcitation with e as the column's event, its weight as the guided event by drawing the
// guided event at the middle of e's share of u. The expectation of both samples,
// sum over e of p_c w_c L + p_g w_g L, must equal D L_o + sum_i M[i][o] L_i exactly, for a
// light equal to the guide, a broadband light the guide does not describe, and a light where
// the guide is dark (the column's regime). With the guide flat the weights halve the column's.
TEST(ReradiationMatrix, GuidedExcitationMisIsUnbiasedForAnyLight) {
  const RM m = RM::fromModel({440, 80, 20, 10, 0.9, 0.8});
  const ExcitationGuide led = guideOf(royalBlue);
  const double rho = 0.5;
  forEachMisCase(
      m, rho,
      [&](size_t li, const ExcitationGuide& lbar, double nm, int o, double d, double total) {
        double z = d * led.mean[static_cast<size_t>(o)];
        for (int i = 0; i < o; ++i) z += m(i, o) * led.mean[static_cast<size_t>(i)];
        // The guided draw's events in its order (elastic first, then bins upwards): event e is
        // drawn for u in [before(e), before(e) + v g) / z, so its middle lands on it.
        std::vector<double> before(static_cast<size_t>(o) + 1, 0.0);
        double running = d * led.mean[static_cast<size_t>(o)];
        for (int e = 0; e < o; ++e) {
          before[static_cast<size_t>(e)] = running;
          running += m(e, o) * led.mean[static_cast<size_t>(e)];
        }
        double expected = 0, combined = 0;
        for (int e = 0; e <= o; ++e) { // e = o: the elastic event
          const double v = e == o ? d : m(e, o);
          const double l = lbar.mean[static_cast<size_t>(e)], g = led.mean[static_cast<size_t>(e)];
          const float eventNm = e == o ? static_cast<float>(nm) : static_cast<float>(RM::centre(e));
          const float w = m.guidedExcitation(static_cast<float>(nm), eventNm,
                                             static_cast<float>(rho), 1.0f, led, 0.5f, 0.5f)
                              .weight[0];
          EXPECT_GE(w, 0);
          EXPECT_LE(w, total * (1 + 1e-6)); // never more than the column alone
          expected += v * l;
          combined += v / total * w * l;
          if (v * g > 1e-6 * z) { // the guided technique draws e: its own weight there
            const double u = (before[static_cast<size_t>(e)] + 0.5 * v * g) / z;
            const GuidedExcitation ge =
                m.guidedExcitation(static_cast<float>(nm), eventNm, static_cast<float>(rho), 1.0f,
                                   led, static_cast<float>(u), 0.5f);
            ASSERT_NEAR(ge.nm[1], e == o ? nm : RM::centre(e), 1e-3) << "event " << e;
            EXPECT_LE(ge.weight[1], z / g * (1 + 1e-5)); // never more than the guide alone
            combined += v * g / z * ge.weight[1] * l;
          }
        }
        EXPECT_NEAR(combined, expected, 1e-5 * expected + 1e-12)
            << "light " << li << ", " << nm << " nm";
      });
  ExcitationGuide flat;
  flat.mean.fill(1.0f);
  float w = 1;
  const float column = m.sampleExcitation(530, 0.5f, 0.3f, 0.5f, w);
  const GuidedExcitation e = m.guidedExcitation(530, column, 0.5f, 1.0f, flat, 0.7f, 0.5f);
  EXPECT_NEAR(e.weight[0], 0.5 * w, 1e-6);
  EXPECT_NEAR(e.weight[1], 0.5 * w, 1e-6);
}

// With several guides (a relightable render's targets: a blue LED, a green one and a flat
// daylight-like guide), the column's event and each guide's together are still unbiased for any
// light: sum over e of p_c(e) w_c(e) L(e) + sum over t of p_t(e) w_t(e) L(e) equals
// D L_o + sum_i M[i][o] L_i, each weight read back as in the one-guide test (guide t's event
// placed on e by its own u, the others' anywhere; events a guide draws with less than 1e-6 of
// its probability are left out, which with three guides' float weights moves the sum by up to
// 3e-5 of it: the tolerance is 1e-4); with one guide the weights are guidedExcitation's.
TEST(ReradiationMatrix, SeveralGuidesMisIsUnbiasedForAnyLight) {
  const RM m = RM::fromModel({440, 80, 20, 10, 0.9, 0.8});
  const ExcitationGuide blue = guideOf(royalBlue);
  const ExcitationGuide green = guideOf([](double nm) { return royalBlue(nm - 70); });
  const ExcitationGuide day = guideOf([](double nm) { return 0.5 + nm / 2000; });
  ExcitationGuides guides;
  for (const ExcitationGuide* g : {&blue, &green, &day}) guides.guide[guides.count++] = g;
  const double rho = 0.5;
  forEachMisCase(
      m, rho,
      [&](size_t li, const ExcitationGuide& lbar, double nm, int o, double d, double total) {
        double expected = 0, combined = 0;
        for (int e = 0; e <= o; ++e) { // e = o: the elastic event
          const double v = e == o ? d : m(e, o), l = lbar.mean[static_cast<size_t>(e)];
          const float eventNm = e == o ? static_cast<float>(nm) : static_cast<float>(RM::centre(e));
          expected += v * l;
          RM::Sample2Pair uv[kMaxExcitationGuides];
          for (auto& x : uv) x = {0.5f, 0.5f};
          GuidedExcitations ge;
          m.guidedExcitations(static_cast<float>(nm), eventNm, static_cast<float>(rho), 1.0f,
                              guides, uv, ge);
          EXPECT_LE(ge.weight[0], total * (1 + 1e-6));
          combined += v / total * ge.weight[0] * l;
          for (int t = 0; t < guides.count; ++t) {
            const ExcitationGuide& g = *guides.guide[t];
            double z = d * g.mean[static_cast<size_t>(o)], before = z;
            for (int i = 0; i < o; ++i) z += m(i, o) * g.mean[static_cast<size_t>(i)];
            for (int i = 0; i < e && e < o; ++i) before += m(i, o) * g.mean[static_cast<size_t>(i)];
            const double ge_ =
                e == o ? d * g.mean[static_cast<size_t>(o)] : v * g.mean[static_cast<size_t>(e)];
            if (!(ge_ > 1e-6 * z)) continue; // guide t does not draw e
            uv[t].u = static_cast<float>(((e == o ? 0.0 : before) + 0.5 * ge_) / z);
            m.guidedExcitations(static_cast<float>(nm), eventNm, static_cast<float>(rho), 1.0f,
                                guides, uv, ge);
            ASSERT_NEAR(ge.nm[t + 1], e == o ? nm : RM::centre(e), 1e-3) << "event " << e;
            combined += ge_ / z * ge.weight[t + 1] * l;
            uv[t].u = 0.5f;
          }
        }
        EXPECT_NEAR(combined, expected, 1e-4 * expected + 1e-12)
            << "light " << li << ", " << nm << " nm";
      });
  // One guide: guidedExcitation's weights.
  ExcitationGuides one;
  one.guide[0] = &blue;
  one.count = 1;
  const RM::Sample2Pair uv{0.3f, 0.6f};
  GuidedExcitations ge;
  m.guidedExcitations(530, 480, 0.5f, 1.0f, one, &uv, ge);
  const GuidedExcitation e = m.guidedExcitation(530, 480, 0.5f, 1.0f, blue, 0.3f, 0.6f);
  EXPECT_EQ(ge.nm[1], e.nm[1]);
  EXPECT_NEAR(ge.weight[0], e.weight[0], 1e-6 * e.weight[0]);
  EXPECT_NEAR(ge.weight[1], e.weight[1], 1e-6 * e.weight[1]);
}

// guideMismatch is E[g^2] / E[g]^2 over the column's events: 1 for a flat guide; 1 / f for a
// guide that is 1 on events of total column probability f and 0 elsewhere; small for a
// daylight black body over the thesis' blue dye (no guidance: no cost under broadband light)
// and large for a royal-blue LED over the same column at the dye's emission.
TEST(ReradiationMatrix, GuideMismatchMeasuresHowUnevenlyTheColumnMeetsALight) {
  const RM m = RM::fromModel({460, 80, 20, 10, 1, 1});
  ExcitationGuide flat;
  flat.mean.fill(1.0f);
  for (double nm : {452.0, 540.0, 601.0})
    EXPECT_NEAR(m.guideMismatch(flat, RM::binOf(nm)), 1.0, 1e-9) << nm;
  const int o = RM::binOf(540), cut = RM::binOf(455);
  ExcitationGuide below = flat;
  for (int i = cut; i < RM::kBins; ++i) below.mean[static_cast<size_t>(i)] = 0;
  double inside = 0, total = m.elastic(o, 1.0);
  for (int i = 0; i < o; ++i) (i < cut ? inside : total) += m(i, o);
  total += inside;
  ASSERT_GT(inside, 0);
  EXPECT_NEAR(m.guideMismatch(below, o), total / inside, 1e-6 * total / inside);
  ExcitationGuide dark = flat;
  dark.mean.fill(0.0f);
  EXPECT_EQ(m.guideMismatch(dark, o), 1.0);

  const ExcitationGuide daylight = guideOf([](double nm) { return BlackbodySpectrum{6504}(nm); });
  const ExcitationGuide led = guideOf(royalBlue);
  const RM thesisBlue = RM::fromModel({460, 220, 20, 10, 1, 1});
  for (double nm : {540.0, 620.0, 680.0})
    EXPECT_LT(thesisBlue.guideMismatch(daylight, RM::binOf(nm)), 1.25) << nm;
  EXPECT_GT(m.guideMismatch(led, o), 2.0);
}

} // namespace
} // namespace nx
