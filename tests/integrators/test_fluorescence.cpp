#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>

#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "spectra/reradiation_matrix.h"
#include "support/errors.h"
#include "support/furnace_solution.h"
#include "support/statistics.h"
#include "support/synthetic_eem.h"

namespace nx {
namespace {

using RM = ReradiationMatrix;

RenderOutput renderText(const std::string& text) {
  return render(buildRenderScene(parseScene(text, "t.scn")), {});
}

using test::bandOfBins;

void expectBandsEqual(const Film& film, const std::function<double(int)>& expected,
                      double precision, const std::string& what) {
  for (int b = 0; b < film.bands().count(); ++b) {
    test::RunningStats s;
    for (int y = 0; y < film.height(); ++y)
      for (int x = 0; x < film.width(); ++x) s.add(film.bandMean(x, y, b));
    const double e = expected(b);
    EXPECT_LT(std::abs(s.mean - e), 5 * s.standardError() + 1e-9)
        << what << " band " << film.bands().centroid(b) << " mean " << s.mean << " expected " << e;
    EXPECT_LT(s.standardError(), precision * std::max(e, 0.1))
        << what << " band " << film.bands().centroid(b);
  }
}

// A camera inside a closed matte sphere (reflectance 0.5) emitting a flat 0.5, fluorescent with
// `fluorescence`'s children.
std::string furnaceText(const std::string& fluorescence) {
  return "<scene><settings><xres>12</xres><yres>12</yres><mode>spectral_mcpt</mode><depth>3"
         "</depth><sampl>256</sampl></settings><camera><position>0,0,0</position><look_at>0,0,1"
         "</look_at></camera><sphere><center>0,0,0</center><radius>1</radius><material>matte"
         "</material><reflectance>0.5</reflectance><emission>0.5</emission><fluorescence>" +
         fluorescence + "</fluorescence></sphere></scene>";
}

struct FurnaceCase {
  std::string fluorescence;
  FluorescenceModel model;
};

// Fluorescent furnace: inside a closed sphere of the fluorescent material emitting a flat Le,
// every 5 nm bin holds L = (I - diag(D) - M^T)^-1 Le, D = (1 - a) rho.
TEST(Fluorescence, FurnaceMatchesTheMatrixSolution) {
  const double rho = 0.5, le = 0.5;
  const std::vector<FurnaceCase> cases = {
      {"<absorption>blue</absorption><stokes>220</stokes>", {460, 220, 20, 10, 1, 1}},
      {"<absorption>uv</absorption><stokes>120</stokes><yield>0.5</yield>",
       {370, 120, 20, 10, 0.5, 1}},
      {"<absorption>450</absorption><stokes>50</stokes><yield>0.8</yield><width>30</width><skew>5</"
       "skew><peak>0.7</peak>",
       {450, 50, 30, 5, 0.8, 0.7}},
  };
  for (const auto& c : cases) {
    const RenderOutput out = renderText(furnaceText(c.fluorescence));
    const std::vector<double> L = test::furnaceRadiance(RM::fromModel(c.model), rho, le);
    expectBandsEqual(
        out.film, [&](int b) { return bandOfBins(L, out.film.bands(), b); }, 0.02, c.fluorescence);
    EXPECT_EQ(out.stats.nonFinite, 0u);
  }
}

// f at the matrix's bin centres as a table of steps, as scene text: constant over each bin
// (its two ends 1e-9 nm inside), so that each bin's mean is f at its centre (the model's value).
std::string binTable(const std::function<double(double)>& f) {
  std::string t;
  for (int i = 0; i < RM::kBins; ++i) {
    const double lo = RM::kMinNm + i * RM::kBinNm, v = f(RM::centre(i));
    for (double nm : {lo + 1e-9, lo + RM::kBinNm - 1e-9}) {
      char b[64];
      std::snprintf(b, sizeof b, "%s%.17g:%.17g", t.empty() ? "" : ", ", nm, v);
      t += b;
    }
  }
  return t;
}

// The model's curves (docs/fluorescence.md) as spectra: absorptance a_max f(l; l_a, g, -w) /
// max f, emission f(l; l_a + S, g, w).
struct ModelCurves {
  FluorescenceModel m;
  double aMax = 0;
  explicit ModelCurves(const FluorescenceModel& model) : m(model) {
    for (int i = 0; i < RM::kBins; ++i) aMax = std::max(aMax, absorption(RM::centre(i)));
  }
  double absorption(double nm) const {
    return SkewCauchySpectrum{m.absorptionPeakNm, m.widthNm, -m.skew}(nm);
  }
  double absorptance(double nm) const { return m.peakAbsorptance * absorption(nm) / aMax; }
  double emission(double nm) const {
    return SkewCauchySpectrum{m.absorptionPeakNm + m.stokesNm, m.widthNm, m.skew}(nm);
  }
};

// A dye given as spectra takes each bin's mean of them. The model's curves written as a fine
// table (every 0.25 nm) give the matrix of their bin means, computed here independently by
// Simpson's rule on the curves (the table's linear interpolation: 1e-3 of a cell); its emission's
// scale does not matter (it is normalised). Those means are the model's own matrix (its curves at
// the bins' centres) to within the midpoint rule's error, 5% of the largest cell for
// this dye 25 nm wide.
TEST(Fluorescence, SeparableDyeOfTheModelsCurvesHasTheirBinMeans) {
  const FluorescenceModel model{450, 60, 25, 8, 0.7, 0.9};
  const ModelCurves curves(model);
  auto table = [](const std::function<double(double)>& f, double scale) {
    std::vector<double> nm, v;
    for (double x = RM::kMinNm; x <= RM::kMaxNm + 1e-9; x += 0.25) {
      nm.push_back(x);
      v.push_back(scale * f(x));
    }
    return Spectrum(TabulatedSpectrum{nm, v});
  };
  auto simpson = [](const std::function<double(double)>& f, double lo, double hi) {
    const int n = 200;
    double sum = f(lo) + f(hi);
    for (int k = 1; k < n; ++k) sum += (k % 2 ? 4 : 2) * f(lo + (hi - lo) * k / n);
    return sum / (3.0 * n);
  };
  std::array<double, RM::kBins> a{}, e{};
  for (int i = 0; i < RM::kBins; ++i) {
    const double lo = RM::kMinNm + i * RM::kBinNm, hi = lo + RM::kBinNm;
    a[i] = simpson([&](double nm) { return curves.absorptance(nm); }, lo, hi);
    e[i] = simpson([&](double nm) { return curves.emission(nm); }, lo, hi);
  }
  const RM expected = RM::fromSpectra(a, e, 0.7);
  const RM separable = separableMatrix(table([&](double nm) { return curves.absorptance(nm); }, 1),
                                       table([&](double nm) { return curves.emission(nm); }, 123.0),
                                       0.7, false, "t");
  const RM model_ = RM::fromModel(model);
  double largest = 0;
  for (int i = 0; i < RM::kBins; ++i)
    for (int o = 0; o < RM::kBins; ++o) largest = std::max(largest, model_(i, o));
  for (int i = 0; i < RM::kBins; ++i) {
    EXPECT_NEAR(separable.absorptance(i), expected.absorptance(i), 1e-3 * a[i] + 1e-12);
    for (int o = 0; o < RM::kBins; ++o) {
      ASSERT_NEAR(separable(i, o), expected(i, o), 1e-3 * expected(i, o) + 1e-12 * largest)
          << i << "," << o;
      ASSERT_NEAR(separable(i, o), model_(i, o), 0.05 * largest) << i << "," << o;
    }
  }
}

// Closed form of the separable matrix for box spectra: a = 0.4 over 400-450 nm, all emission in
// the bin 600-605 nm, yield 0.5: M[i][o] = 0.4 * 0.5 * l_i / l_o there and 0 elsewhere. A line
// narrower than a bin, between two bins' centres, falls into its bin with its integral. An
// emission entirely below the absorption is refused (no fluorescence would render), one
// mostly below it warned about (the EEM import's rule); an absorptance above 1 between two
// bins' centres and other bad spectra are refused; the emission's scale is any (not a light's
// limit).
TEST(Fluorescence, SeparableMatrixOfBoxSpectra) {
  const Spectrum a(TabulatedSpectrum{{400, 450}, {0.4, 0.4}});
  const Spectrum e(TabulatedSpectrum{{600, 605}, {2, 2}});
  const RM m = separableMatrix(a, e, 0.5, false, "t");
  const int em = RM::binOf(602.5);
  for (int i = 0; i < RM::kBins; ++i)
    for (int o = 0; o < RM::kBins; ++o) {
      const bool absorbs = RM::centre(i) > 400 && RM::centre(i) < 450;
      const double want = absorbs && o == em ? 0.2 * RM::centre(i) / RM::centre(o) : 0;
      ASSERT_NEAR(m(i, o), want, 1e-13) << i << "," << o;
    }
  // a 0.02 nm line at 601.01 nm, off its bin's centre: the same matrix (it is all in bin 600-605)
  const Spectrum line(TabulatedSpectrum{{601, 601.01, 601.02}, {0, 5e13, 0}});
  const RM lined = separableMatrix(a, line, 0.5, false, "t");
  for (int i = 0; i < RM::kBins; ++i) ASSERT_NEAR(lined(i, em), m(i, em), 1e-13) << i;
  std::string warning;
  EXPECT_NE(test::errorMessage([&] { separableMatrix(e.scaled(0.1), a, 1, false, "t.scn:4"); })
                .find("t.scn:4: expected a dye that emits at longer wavelengths than it absorbs "
                      "(the matrix models Stokes-shifted light only), found 0% of its emission"),
            std::string::npos);
  // two thirds of the emission below the absorption band: under half modelled, warned
  const Spectrum split(TabulatedSpectrum{{380, 420, 420.001, 600, 640}, {1, 1, 0, 0, 1}});
  (void)separableMatrix(a, split, 1, false, "t.scn:5", &warning);
  EXPECT_EQ(warning.rfind("t.scn:5: warning: the dye's emission is mostly at or below its "
                          "absorption: ",
                          0),
            0u)
      << warning;
  const std::string over =
      test::errorMessage([&] { separableMatrix(a.scaled(3), e, 1, false, "t.scn:4"); });
  EXPECT_EQ(over.rfind("t.scn:4: expected an absorptance within [0, 1], found 1.2 at", 0), 0u)
      << over;
  const Spectrum spike(
      TabulatedSpectrum{{400, 412.4, 412.5, 412.6, 450}, {0.4, 0.4, 1.7, 0.4, 0.4}});
  EXPECT_EQ(test::errorMessage([&] { separableMatrix(spike, e, 1, false, "t.scn:4"); }),
            "t.scn:4: expected an absorptance within [0, 1], found 1.7 at 412.5 nm");
  EXPECT_EQ(test::errorMessage(
                [&] { separableMatrix(a, Spectrum(ConstantSpectrum{0}), 1, false, "t.scn:4"); }),
            "t.scn:4: expected an emission spectrum above 0 somewhere in 300-1100 nm, found 0 "
            "everywhere");
  // A medium's dye: its absorptance is a shape (any scale), scaled to 1 at its largest bin.
  const RM shape = separableMatrix(a.scaled(3), e, 0.5, true, "t");
  EXPECT_NEAR(shape.absorptance(RM::binOf(420)), 1.0, 1e-15);
}

// Rendered, a surface and a medium whose dyes are the model's curves written as spectra (steps
// over the bins, whose means are the curves at the centres) render as the model: the furnace's
// matrix solution, and the medium's image against the model's.
TEST(Fluorescence, SeparableDyeRendersAsTheModelItTabulates) {
  const FluorescenceModel model{460, 80, 20, 10, 0.8, 1};
  const ModelCurves curves(model);
  const std::string spectra =
      "<absorptance>" + binTable([&](double nm) { return curves.absorptance(nm); }) +
      "</absorptance><emission>" + binTable([&](double nm) { return curves.emission(nm); }) +
      "</emission><yield>0.8</yield>";
  const RenderOutput out = renderText(furnaceText(spectra));
  const std::vector<double> L = test::furnaceRadiance(RM::fromModel(model), 0.5, 0.5);
  expectBandsEqual(
      out.film, [&](int b) { return bandOfBins(L, out.film.bands(), b); }, 0.02, "separable");
  // In a medium: the same image as the model dye of the same peak coefficient.
  auto medium = [](const std::string& dye) {
    return renderText(
        "<scene><settings><xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode><depth>6</depth>"
        "<sampl>64</sampl><bands>400:700:50</bands></settings><camera><position>0,0,-3</position>"
        "<look_at>0,0,0</look_at><fov>30</fov></camera><sphere><center>0,0,0</center><radius>"
        "0.8</radius><material>interface</material><medium><sigma_a>0.1</sigma_a><sigma_s>0.5"
        "</sigma_s><fluorescence>" +
        dye +
        "<peak>2</peak></fluorescence></medium></sphere><sphere><center>0,3,-2</center>"
        "<radius>0.5</radius><material>matte</material><reflectance>0</reflectance>"
        "<emission>blackbody:6500</emission></sphere></scene>");
  };
  const RenderOutput asModel = medium("<absorption>460</absorption><stokes>80</stokes>"
                                      "<yield>0.8</yield>");
  const RenderOutput asSpectra = medium(spectra);
  for (int b = 0; b < asModel.film.bands().count(); ++b)
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x)
        EXPECT_NEAR(asSpectra.film.bandMean(x, y, b), asModel.film.bandMean(x, y, b),
                    1e-6 * std::abs(asModel.film.bandMean(x, y, b)) + 1e-12)
            << b << " " << x << " " << y;
}

// The same furnace emitting only a royal-blue LED's narrow band (450 nm, FWHM 20 nm) onto a dye
// absorbing there (blue, Stokes 80): next-event estimation picks the emitting sphere, so the
// excitation is drawn from the column and from the light's spectrum and combined by MIS; the
// bands match L = (I - D - M^T)^-1 Le with Le the LED's 5 nm bin means, the LED's own bands and
// the dye's emission bands alike.
TEST(Fluorescence, FurnaceUnderANarrowBandEmitterMatchesTheMatrixSolution) {
  const double rho = 0.5;
  const RenderOutput out = renderText(
      "<scene><settings><xres>12</xres><yres>12</yres><mode>spectral_mcpt</mode><depth>4</depth>"
      "<sampl>256</sampl></settings><camera><position>0,0,0</position><look_at>0,0,1</look_at>"
      "</camera><sphere><center>0,0,0</center><radius>1</radius><material>matte</material>"
      "<reflectance>0.5</reflectance><emission>" +
      test::royalBlueLedText() +
      "</emission><fluorescence><absorption>blue</absorption><stokes>80</stokes></fluorescence>"
      "</sphere></scene>");
  const std::vector<double> L = test::furnaceRadiance(RM::fromModel({460, 80, 20, 10, 1, 1}), rho,
                                                      test::binMeans(test::royalBlueLed));
  // The dye's emission is a real share of the image (the test is not only the LED's reflection).
  int dyeBand = 0;
  for (int b = 0; b < out.film.bands().count(); ++b)
    if (std::abs(out.film.bands().centroid(b) - 540) < 1) dyeBand = b;
  EXPECT_GT(bandOfBins(L, out.film.bands(), dyeBand), 0.05);
  expectBandsEqual(
      out.film, [&](int b) { return bandOfBins(L, out.film.bands(), b); }, 0.02, "narrow LED");
  EXPECT_EQ(out.stats.nonFinite, 0u);
}

// Quantum yield 0 is the plain material with rho replaced by (1 - a) rho: both furnaces
// match L = Le / (1 - (1 - a) rho) per bin.
TEST(Fluorescence, ZeroYieldEqualsReducedReflectance) {
  const RM m = RM::fromModel({460, 100, 20, 10, 0, 1});
  std::vector<double> L(RM::kBins);
  std::string steps; // (1 - a) rho as a step function on the grid
  for (int o = 0; o < RM::kBins; ++o) {
    L[o] = 0.5 / (1 - m.elastic(o, 0.6));
    const double lo = RM::kMinNm + o * RM::kBinNm;
    steps += (o ? ", " : "") + std::to_string(lo) + ":" + std::to_string(m.elastic(o, 0.6)) + ", " +
             std::to_string(lo + RM::kBinNm - 1e-4) + ":" + std::to_string(m.elastic(o, 0.6));
  }
  const std::string head =
      "<scene><settings><xres>12</xres><yres>12</yres><mode>spectral_mcpt</mode><depth>3</depth>"
      "<sampl>256</sampl></settings><camera><position>0,0,0</position><look_at>0,0,1</look_at>"
      "</camera><sphere><center>0,0,0</center><radius>1</radius><material>matte</material>";
  const RenderOutput fluorescent =
      renderText(head + "<reflectance>0.6</reflectance><emission>0.5</emission><fluorescence>"
                        "<absorption>blue</absorption><stokes>100</stokes><yield>0</yield>"
                        "</fluorescence></sphere></scene>");
  const RenderOutput plain = renderText(head + "<reflectance>" + steps +
                                        "</reflectance><emission>0.5</emission></sphere></scene>");
  expectBandsEqual(
      fluorescent.film, [&](int b) { return bandOfBins(L, fluorescent.film.bands(), b); }, 0.02,
      "Q = 0");
  expectBandsEqual(
      plain.film, [&](int b) { return bandOfBins(L, plain.film.bands(), b); }, 0.02, "(1 - a) rho");
}

// Stokes ordering: a fluorescent surface lit only in the 380-385 nm bin shows radiance only at
// longer wavelengths; with rho = 0 nothing at all appears at or below the excitation band.
TEST(Fluorescence, StokesShiftOnlyTowardsLongerWavelengths) {
  const RenderOutput out =
      renderText("<scene><settings><xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode><depth>3</"
                 "depth><sampl>64</sampl>"
                 "<bands>310:800:10</bands><background>380:1, 385:1</background></settings>"
                 "<camera><position>0,0,-4</position><look_at>0,0,0</look_at><fov>10</fov></camera>"
                 "<sphere><center>0,0,0</center><radius>1</radius><material>matte</"
                 "material><reflectance>null</reflectance>"
                 "<fluorescence><absorption>uv</absorption><stokes>100</stokes></fluorescence></"
                 "sphere></scene>");
  const Film& f = out.film;
  double visible = 0;
  for (int b = 0; b < f.bands().count(); ++b)
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) {
        const double v = f.bandMean(x, y, b);
        if (f.bands().channel(b).hi <= 385) {
          EXPECT_EQ(v, 0.0) << "band " << f.bands().centroid(b);
        }
        if (f.bands().centroid(b) >= 440 && f.bands().centroid(b) <= 520) visible += v;
      }
  EXPECT_GT(visible, 0.0);
}

// Energy: with rho = 0 and Q = 1, a convex fluorescent object under a background that emits
// only below the absorption edge returns, per bin, exactly sum_i M[i][o] Lbg(i) (one
// bounce), and never more energy than it receives.
TEST(Fluorescence, EnergyIsConservedAndSingleBounceMatchesTheMatrix) {
  const RenderOutput out =
      renderText("<scene><settings><xres>10</xres><yres>10</yres><mode>spectral_mcpt</"
                 "mode><depth>3</depth><sampl>256</sampl>"
                 "<bands>400:820:10</bands><background>360:1, 400:1</background></settings>"
                 "<camera><position>0,0,-4</position><look_at>0,0,0</look_at><fov>12</fov></camera>"
                 "<sphere><center>0,0,0</center><radius>1</radius><material>matte</"
                 "material><reflectance>null</reflectance>"
                 "<fluorescence><absorption>uv</absorption><stokes>120</stokes></fluorescence></"
                 "sphere></scene>");
  const RM m = RM::fromModel({370, 120, 20, 10, 1, 1});
  std::vector<double> perBin(RM::kBins, 0.0);
  double incoming = 0, outgoing = 0;
  const int first = RM::binOf(360), last = RM::binOf(400); // Lbg = 1 over 360-400 nm
  for (int i = first; i < last; ++i) incoming += RM::kBinNm;
  for (int o = 0; o < RM::kBins; ++o) {
    for (int i = first; i < last; ++i) perBin[o] += m(i, o);
    outgoing += perBin[o] * RM::kBinNm;
  }
  EXPECT_LT(outgoing, incoming);
  expectBandsEqual(
      out.film, [&](int b) { return bandOfBins(perBin, out.film.bands(), b); }, 0.05,
      "single bounce");
  double rendered = 0;
  for (int b = 0; b < out.film.bands().count(); ++b) rendered += out.film.bandMean(5, 5, b) * 10;
  EXPECT_LT(rendered, incoming);
}

} // namespace
} // namespace nx

namespace nx {
namespace {

// A fluorescence-only measured matrix (no excitation wavelength equals an emission one, as an
// instrument EEM gives): the surface's elastic part is its <reflectance> (it was 0 before, the
// reflectance silently ignored), the build says so, and the energy check counts the
// reflectance with the re-radiated light.
TEST(Fluorescence, MatrixWithoutDiagonalTakesItsElasticPartFromTheReflectance) {
  const std::string csv = ::testing::TempDir() + "/eem_no_diagonal.csv";
  {
    std::ofstream f(csv);
    f << "ex,600,650,700\n350,0.02,0.04,0.02\n400,0.02,0.04,0.02\n";
  }
  auto scene = [&](const std::string& reflectance) {
    // A quad filling the view under a uniform background of 1, one bounce: its radiance in
    // bands away from the matrix's emission is its elastic reflectance.
    return "<scene><settings><xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode><sampl>64"
           "</sampl><depth>1</depth><background>1</background><bands>450:550:50</bands>"
           "</settings><camera><position>0,0,-1</position><look_at>0,0,0</look_at><fov>20</fov>"
           "</camera><quad><origin>-1,-1,0</origin><edge_u>2,0,0</edge_u><edge_v>0,2,0</edge_v>"
           "<material>matte</material>" +
           reflectance + "<fluorescence><matrix>" + csv + "</matrix></fluorescence></quad></scene>";
  };
  const RenderScene s =
      buildRenderScene(parseScene(scene("<reflectance>0.86</reflectance>"), "t.scn"));
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("t.scn:1: warning: the measured matrix"), std::string::npos);
  EXPECT_NE(s.warnings[0].find("has no diagonal"), std::string::npos) << s.warnings[0];
  EXPECT_NE(s.warnings[0].find("the material's <reflectance>"), std::string::npos) << s.warnings[0];
  const RenderOutput out = render(s, RenderOptions{});
  for (int b = 0; b < out.film.bands().count(); ++b) {
    test::RunningStats st;
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) st.add(out.film.bandMean(x, y, b));
    EXPECT_NEAR(st.mean, 0.86, 5 * st.standardError() + 1e-3) << "band " << b;
  }
  // The reflectance plus the re-radiated light above 1 is refused, naming the reflectance.
  try {
    (void)buildRenderScene(parseScene(scene("<reflectance>0.97</reflectance>"), "t.scn"));
    ADD_FAILURE() << "an albedo above 1 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("the surface's <reflectance>: the matrix has no diagonal"),
              std::string::npos)
        << e.what();
  }
  // A matrix with a diagonal keeps it: no warning.
  const std::string withDiagonal = ::testing::TempDir() + "/eem_diagonal.csv";
  {
    std::ofstream f(withDiagonal);
    f << "ex,400,600\n400,0.5,0.04\n600,0,0.5\n";
  }
  std::string text = scene("<reflectance>0.86</reflectance>");
  text.replace(text.find(csv), csv.size(), withDiagonal);
  EXPECT_TRUE(buildRenderScene(parseScene(text, "t.scn")).warnings.empty());
  // A diagonal of zeros (a fluorescence-only measurement written as a full matrix) is taken
  // as none: the elastic part is the <reflectance> (it was 0, the reflectance ignored), said.
  const std::string zeroDiagonal = ::testing::TempDir() + "/eem_zero_diagonal.csv";
  std::ofstream(zeroDiagonal) << "ex,350,400,590,600,650,700\n350,0,0,0,0.02,0.04,0.02\n"
                                 "400,0,0,0,0.02,0.04,0.02\n";
  text = scene("<reflectance>0.86</reflectance>");
  text.replace(text.find(csv), csv.size(), zeroDiagonal);
  const RenderScene z = buildRenderScene(parseScene(text, "t.scn"));
  ASSERT_EQ(z.warnings.size(), 1u);
  EXPECT_NE(z.warnings[0].find("has a diagonal of zeros (a fluorescence-only measurement), taken "
                               "as no diagonal: its elastic reflectance is the material's "
                               "<reflectance>"),
            std::string::npos)
      << z.warnings[0];
  ASSERT_TRUE(z.materials[0].reradiation->zeroDiagonal());
  const RenderOutput zOut = render(z, RenderOptions{});
  for (int b = 0; b < zOut.film.bands().count(); ++b) {
    test::RunningStats st;
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) st.add(zOut.film.bandMean(x, y, b));
    EXPECT_NEAR(st.mean, 0.86, 5 * st.standardError() + 1e-3) << "band " << b;
  }
}

// An instrument EEM (Rayleigh and Raman lines, instrument grids, counts) imported from the
// scene file renders as the dye it was synthesised from: a quad under a uniform background of
// 1, one bounce, has radiance rho + c(o) (c the model's column sums, averaged over each band),
// z-tested; the import is noted, and the elastic part is the <reflectance>.
TEST(Fluorescence, ImportedEemRendersAsTheModelDye) {
  const test::Dye dye;
  test::Synthetic syn;
  syn.ex = test::grid(250, 600, 5);
  syn.em = test::grid(300, 1100, 2);
  const std::string csv = ::testing::TempDir() + "/dye_eem.csv";
  std::ofstream(csv) << syn.csv(dye);
  const double rho = 0.2;
  const std::string text =
      "<scene><settings><xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode><sampl>64"
      "</sampl><depth>1</depth><background>1</background><bands>520:640:40</bands>"
      "</settings><camera><position>0,0,-1</position><look_at>0,0,0</look_at><fov>20</fov>"
      "</camera><quad><origin>-1,-1,0</origin><edge_u>2,0,0</edge_u><edge_v>0,2,0</edge_v>"
      "<material>matte</material><reflectance>0.2</reflectance><fluorescence>\n"
      "<eem file=\"" +
      csv +
      "\" rayleigh_width=\"12\" raman_shift=\"water\" raman_width=\"12\" "
      "emission_shape=\"mean\"/><yield>0.6</yield><peak>0.9</peak></fluorescence></quad></scene>";
  const RenderScene s = buildRenderScene(parseScene(text, "t.scn"));
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("t.scn:2: note: the EEM"), std::string::npos) << s.warnings[0];
  EXPECT_NE(s.warnings[0].find("quantum yield 0.6"), std::string::npos) << s.warnings[0];
  ASSERT_TRUE(s.materials[0].reradiation->elasticFromReflectance());
  const ReradiationMatrix model = ReradiationMatrix::fromModel(dye.model());
  const RenderOutput out = render(s, RenderOptions{});
  for (int b = 0; b < out.film.bands().count(); ++b) {
    const double lo = 500 + 40 * b; // bands centred 520, 560, ..., 40 nm wide
    double want = 0;
    for (int o = ReradiationMatrix::binOf(lo); o < ReradiationMatrix::binOf(lo + 40); ++o)
      want += (rho + model.columnSum(o)) / 8;
    test::RunningStats st;
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) st.add(out.film.bandMean(x, y, b));
    // The EEM's grid resamples the model's absorption edge (a few per cent: the unit tests).
    EXPECT_NEAR(st.mean, want, 5 * st.standardError() + 0.03 * want) << "band " << b;
  }
  // Its emission window (300-1100 nm) holds all the dye emits: nothing to warn about.
  EXPECT_TRUE(extrapolationWarnings(s, 360, 830).empty());
}

// An EEM whose emission window ends where the dye still emits (300-580 nm, the emission peaking
// at 540 nm) misses the light beyond: a render tracing past the window's end warns, naming the
// share left at that end; one tracing within it does not.
TEST(Fluorescence, EemEmissionWindowEndingInsideTheTracedRangeWarns) {
  const test::Dye dye;
  test::Synthetic syn;
  syn.ex = test::grid(250, 500, 5);
  syn.em = test::grid(300, 580, 2);
  const std::string csv = ::testing::TempDir() + "/dye_eem_short.csv";
  std::ofstream(csv) << syn.csv(dye);
  const std::string text =
      "<scene><settings><xres>2</xres><yres>2</yres><mode>spectral_mcpt</mode></settings>"
      "<camera><position>0,0,-1</position><look_at>0,0,0</look_at></camera><quad><origin>-1,-1,"
      "0</origin><edge_u>2,0,0</edge_u><edge_v>0,2,0</edge_v><material>matte</material>"
      "<reflectance>0.2</reflectance><fluorescence>\n<eem file=\"" +
      csv +
      "\" rayleigh_width=\"12\" raman_shift=\"water\" raman_width=\"12\"/><yield>0.6</yield>"
      "<peak>0.9</peak></fluorescence></quad></scene>";
  const RenderScene s = buildRenderScene(parseScene(text, "t.scn"));
  const std::vector<std::string> w = extrapolationWarnings(s, 360, 830);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].substr(0, w[0].find(" its emission is still")),
            "t.scn:2: warning: the EEM " + csv +
                " measures emission over 300-580 nm and this render traces 360-830 nm: at 580 nm");
  EXPECT_NE(w[0].find("of its peak, and the matrix is 0 beyond it (the dye's light there is "
                      "missing: measure a wider emission window)"),
            std::string::npos)
      << w[0];
  const double share = std::stod(w[0].substr(w[0].find("still ") + 6));
  EXPECT_GT(share, 5.0); // per cent: the tail at 580 nm of a dye emitting around 540 nm
  EXPECT_TRUE(extrapolationWarnings(s, 400, 560).empty()); // traced within the window
}

// Most of a dye's photons where the render does not look: an EEM emitting mostly beyond the
// matrix's 1100 nm warns at the build (it was a note that read like a good import), and one
// emitting mostly beyond the traced bands warns for that render.
TEST(Fluorescence, EemMostlyOutsideWhatIsRenderedWarns) {
  auto sceneWith = [](const std::string& csv) {
    return "<scene><settings><xres>2</xres><yres>2</yres><mode>spectral_mcpt</mode></settings>"
           "<camera><position>0,0,-1</position><look_at>0,0,0</look_at></camera><quad><origin>"
           "-1,-1,0</origin><edge_u>2,0,0</edge_u><edge_v>0,2,0</edge_v><material>matte"
           "</material><reflectance>0.2</reflectance><fluorescence>\n<eem file=\"" +
           csv +
           "\" rayleigh_width=\"0\"/><yield>0.6</yield><peak>0.9</peak></fluorescence></quad>"
           "</scene>";
  };
  test::Dye infrared;
  infrared.la = 1000, infrared.stokes = 100, infrared.skew = 0;
  test::Synthetic syn;
  syn.ex = test::grid(950, 1050, 5);
  syn.em = test::grid(960, 1300, 5);
  syn.rayleigh = syn.raman = 0;
  const std::string far = ::testing::TempDir() + "/dye_eem_infrared.csv";
  std::ofstream(far) << syn.csv(infrared);
  const RenderScene s = buildRenderScene(parseScene(sceneWith(far), "t.scn"));
  bool warned = false;
  for (const std::string& w : s.warnings)
    warned |= w.find("t.scn:2: warning: the EEM " + far +
                     " is mostly outside what the matrix models: ") == 0 &&
              w.find("% outside 300-1100 nm (the dye's light there is missing from the render)") !=
                  std::string::npos;
  EXPECT_TRUE(warned) << testing::PrintToString(s.warnings);
  // A visible dye (emission around 540 nm) rendered in the near infrared only.
  const test::Dye visible;
  test::Synthetic vis;
  vis.ex = test::grid(300, 600, 5);
  vis.em = test::grid(300, 1100, 5);
  vis.rayleigh = vis.raman = 0;
  const std::string near = ::testing::TempDir() + "/dye_eem_visible.csv";
  std::ofstream(near) << vis.csv(visible);
  const RenderScene v = buildRenderScene(parseScene(sceneWith(near), "t.scn"));
  for (const std::string& w : v.warnings) EXPECT_EQ(w.find("warning"), std::string::npos) << w;
  EXPECT_TRUE(extrapolationWarnings(v, 400, 700).empty());
  const std::vector<std::string> w = extrapolationWarnings(v, 700, 1000);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].find("t.scn:2: warning: the EEM " + near + " emits 9"), 0u) << w[0];
  EXPECT_NE(w[0].find("% of its modelled photons outside the 700-1000 nm this render traces"),
            std::string::npos)
      << w[0];
}

} // namespace
} // namespace nx
