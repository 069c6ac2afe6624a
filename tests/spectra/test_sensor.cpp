#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "spectra/sensor.h"
#include "spectra/wavelength_sampler.h"
#include "support/errors.h"

namespace nx {
namespace {

// A polynomial spectrum, tabulated finely enough (0.01 nm) that interpolation is exact to 1e-9.
Spectrum polynomial(double c0, double c1, double c2, double c3, double x0) {
  std::vector<double> nm, v;
  for (double l = 300; l <= 1100.0001; l += 0.01) {
    const double x = l - x0;
    nm.push_back(l);
    v.push_back(c0 + x * (c1 + x * (c2 + x * c3)));
  }
  return Spectrum(makeTabulated(nm, v, "polynomial"));
}

// What the film records for spectrum s in every band: integral over the traced wavelengths of
// s(l) * (R_b(l) / integral R_b), by the midpoint rule over a million strata (the film's lookup,
// not the sensor's own quadrature).
std::vector<double> filmIntegral(const Sensor& sensor, const Spectrum& s) {
  const SensorResponseTable table(sensor);
  std::vector<double> out(static_cast<size_t>(sensor.count()), 0.0);
  const int n = 1 << 20;
  const double lo = sensor.minNm(), h = (sensor.maxNm() - lo) / n;
  for (int k = 0; k < n; ++k) {
    const double l = lo + (k + 0.5) * h;
    table.forEach(static_cast<float>(l), [&](int b, float w) { out[b] += s(l) * w * h; });
  }
  return out;
}

// A Gaussian response of standard deviation sigma averages a cubic c0 + c1 x + c2 x^2 + c3 x^3
// (x = l - centre) to c0 + c2 sigma^2 (odd moments vanish).
TEST(Sensor, GaussianBandsAverageAPolynomialAsTheClosedFormSays) {
  const Sensor s = Sensor::parse("gaussian:450,612.5,890@7,12.5,30");
  ASSERT_EQ(s.count(), 3);
  const double centres[3] = {450, 612.5, 890}, fwhm[3] = {7, 12.5, 30};
  for (int b = 0; b < 3; ++b) {
    const double sigma = fwhm[b] / (2 * std::sqrt(2 * std::log(2.0)));
    const Spectrum p = polynomial(2, 0.01, 1e-3, 2e-6, centres[b]);
    const double expected = 2 + 1e-3 * sigma * sigma;
    EXPECT_NEAR(s.average(p, b), expected, 1e-5 * expected) << b;
    EXPECT_NEAR(filmIntegral(s, p)[static_cast<size_t>(b)], expected, 1e-4 * expected) << b;
    EXPECT_DOUBLE_EQ(s.centroid(b), centres[b]);
    EXPECT_DOUBLE_EQ(s.fwhm(b), fwhm[b]);
  }
}

// A measured triangle from 500 to 520 nm (peak at 510): the mean of l^2 under it is
// 510^2 + w^2 / 6 for the half-width w = 10; a ramp's centroid is two thirds along it.
TEST(Sensor, TabulatedBandsAgainstClosedForms) {
  const Sensor s = Sensor::fromCsv("nm,tri,ramp\n480,0,0\n500,0,0\n510,1,0.5\n520,0,1\n"
                                   "520.5,0,0\n540,0,0\n",
                                   "srf.csv");
  ASSERT_EQ(s.count(), 2);
  EXPECT_EQ(s.channel(0).name, "tri");
  EXPECT_DOUBLE_EQ(s.channel(0).lo, 500);
  EXPECT_DOUBLE_EQ(s.channel(0).hi, 520);
  const Spectrum square = polynomial(0, 0, 1, 0, 0);
  const double expected = 510.0 * 510.0 + 100.0 / 6;
  EXPECT_NEAR(s.average(square, 0), expected, 1e-6 * expected);
  EXPECT_NEAR(filmIntegral(s, square)[0], expected, 1e-5 * expected);
  EXPECT_NEAR(s.centroid(0), 510, 1e-9);
  EXPECT_NEAR(s.fwhm(0), 10, 1e-9);
  // Ramp 500 -> 520 (0 -> 1) then 520 -> 520.5 (1 -> 0): centroid of the two triangles.
  const double a1 = 10, m1 = 500 + 2.0 / 3 * 20, a2 = 0.25, m2 = 520 + 0.5 / 3;
  EXPECT_NEAR(s.centroid(1), (a1 * m1 + a2 * m2) / (a1 + a2), 1e-9);
  // A constant spectrum is recorded exactly through every response.
  const Spectrum one(ConstantSpectrum{1});
  for (double v : filmIntegral(s, one)) EXPECT_NEAR(v, 1.0, 1e-6);
}

TEST(Sensor, BoxesKeepTheirExactEdgesAndAverages) {
  const Sensor uniform(SpectralBands::parse("400:700:10"));
  EXPECT_TRUE(uniform.uniformBoxes());
  EXPECT_EQ(uniform.toString(), "400:700:10");
  EXPECT_DOUBLE_EQ(uniform.minNm(), 395);
  EXPECT_DOUBLE_EQ(uniform.maxNm(), 705);
  // Edges are cell edges: a wavelength just inside a band counts for that band alone.
  const SensorResponseTable table(uniform);
  for (float nm : {395.01f, 404.99f, 405.01f, 704.99f}) {
    int hits = 0, band = -1;
    table.forEach(nm, [&](int b, float w) {
      ++hits;
      band = b;
      EXPECT_FLOAT_EQ(w, 0.1f);
    });
    EXPECT_EQ(hits, 1) << nm;
    EXPECT_EQ(band, static_cast<int>((nm - 395) / 10)) << nm;
  }
  int outside = 0;
  table.forEach(705.01f, [&](int, float) { ++outside; });
  EXPECT_EQ(outside, 0);
  // Non-uniform boxes: integral of a linear spectrum / width = its value at the centre.
  const Sensor boxes = Sensor::parse("boxes:400-410,410-437.5,900-1000");
  EXPECT_FALSE(boxes.uniformBoxes());
  const Spectrum line = polynomial(1, 0.01, 0, 0, 300);
  const double centres[3] = {405, 423.75, 950};
  const auto film = filmIntegral(boxes, line);
  for (int b = 0; b < 3; ++b) {
    EXPECT_DOUBLE_EQ(boxes.centroid(b), centres[b]);
    EXPECT_NEAR(boxes.average(line, b), line(centres[b]), 1e-9);
    // The strata (0.57 pm) do not fall on the box edges: up to one stratum's share off.
    EXPECT_NEAR(film[static_cast<size_t>(b)], line(centres[b]), 1e-4 * line(centres[b]));
  }
}

TEST(Sensor, TextFormReadsBackAsTheSameSensor) {
  for (const char* text : {"400:700:10", "boxes:400-410,410-437.5,900-1000", "gaussian:450,612.5@7",
                           "gaussian:500.25,600@7,8.125", "gaussian:400:1000:20@7",
                           "table:nm,a,b\n500,0,0\n510,1,0.25\n520,0,1\n521,0,0\n"}) {
    const Sensor s = Sensor::parse(text);
    const Sensor back = Sensor::parse(s.toString());
    ASSERT_EQ(back.count(), s.count()) << text;
    EXPECT_EQ(back.toString(), s.toString()) << text;
    for (int b = 0; b < s.count(); ++b) {
      EXPECT_EQ(back.centroid(b), s.centroid(b)) << text;
      EXPECT_EQ(back.fwhm(b), s.fwhm(b)) << text;
    }
  }
  EXPECT_EQ(Sensor::parse("gaussian:400:1000:20@7").count(), 31);
}

TEST(Sensor, BadResponsesAreRefusedWithTheirPlace) {
  const std::pair<std::string, std::string> cases[] = {
      {"nm,a\n500,0\n510,-0.5\n", "srf.csv:3: expected a non-negative response for band 'a', "
                                  "found -0.5"},
      {"nm,a,b\n500,0,0\n510,0,1\n520,0,0\n",
       "srf.csv: expected a response above zero somewhere for band 'a', found only zeros"},
      {"500,1\n510,1\n", "srf.csv:1: expected a header 'nm,<band name>,...' naming at least one "
                         "band, found no header"},
      {"nm\n500\n", "srf.csv:1: expected a header 'nm,<band name>,...' naming at least one band, "
                    "found 'nm' alone"},
      {"nm,a,a\n500,0,0\n510,1,1\n520,0,0\n",
       "srf.csv:1: expected distinct, non-empty band names, found 'a' twice"},
      {"nm,a\n500,0\n510,1\n505,0\n",
       "srf.csv:4: expected wavelengths in increasing order, found 505 nm after 510 nm"},
      {"nm,a,b\n500,0\n", "srf.csv:2: expected 3 values (wavelength and one response per band), "
                          "found 2"},
      {"nm,a\n1090,0\n1100,1\n1110,0\n",
       "srf.csv: expected every band within 300-1100 nm, found band 'a' responding over "
       "1090-1110 nm"},
      {"nm,a,b\n500,0,0\n510,1,1\n520,0,0\n",
       "srf.csv: expected bands with distinct centroids (they name the image's channels), found "
       "two at 510.000000 nm"},
  };
  for (const auto& [csv, message] : cases)
    EXPECT_EQ(test::errorMessage([&] { Sensor::fromCsv(csv, "srf.csv"); }), message) << csv;
  const std::pair<std::string, std::string> specs[] = {
      {"gaussian:1090@10", "sensor: expected every band within 300-1100 nm, found band '1090 nm' "
                           "responding over 1070-1110 nm"},
      {"gaussian:500,600@7,8,9", "sensor: expected one FWHM or one per centre (2), found 3"},
      {"gaussian:500@0", "sensor: expected a FWHM of at least 0.1 nm, found 0 nm for the band at "
                         "500 nm"},
      {"gaussian:500", "sensor: expected gaussian:CENTRES@FWHM, found 'gaussian:500'"},
      {"gaussian:5x0@7", "sensor: expected a wavelength in nm, found '5x0'"},
      {"boxes:410-400", "sensor: expected a box at least 0.001 nm wide (LO < HI), found '410-400'"},
      {"boxes:400", "sensor: expected boxes as LO-HI in nm, found '400'"},
      {"boxes:250-260", "sensor: expected every band within 300-1100 nm, found band '255 nm' "
                        "responding over 250-260 nm"},
  };
  for (const auto& [spec, message] : specs)
    EXPECT_EQ(test::errorMessage([&] { Sensor::parse(spec); }), message) << spec;
}

} // namespace
} // namespace nx

namespace nx {
namespace {

// Responses are relative: a measured sensor in any finite scale (counts, 1e308, 1e-300) is the
// same sensor, with finite centroids and a wavelength sampler that returns (at 1e308 the
// integrals overflowed to a NaN centroid; at 1e-310 the sampler's weighting never ended).
TEST(Sensor, MeasuredResponsesInAnyScaleAreTheSameSensor) {
  const auto text = [](double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return std::string(buf);
  };
  const auto scaled = [&](double s) {
    return Sensor::fromCsv("nm,a,b\n480,0,0\n500," + text(s) + ",0\n510," + text(0.5 * s) + "," +
                               text(s) + "\n520,0,0\n",
                           "srf.csv");
  };
  const Sensor one = scaled(1);
  for (double s : {1e308, 1.7e308, 1e-300, 3e-308}) {
    const Sensor x = scaled(s);
    for (int b = 0; b < 2; ++b) {
      EXPECT_TRUE(std::isfinite(x.centroid(b))) << s;
      EXPECT_NEAR(x.centroid(b), one.centroid(b), 1e-9) << s;
      EXPECT_NEAR(x.fwhm(b), one.fwhm(b), 1e-9) << s;
    }
    const WavelengthSampler sampler = WavelengthSampler::forSensor(x, 300, 1100);
    EXPECT_TRUE(std::isfinite(sampler.wavelength(0.5))) << s;
  }
  // Below the normal range the shape is not representable: refused, not guessed.
  EXPECT_EQ(test::errorMessage([&] { scaled(1e-310); }),
            "srf.csv: expected band 'a' to peak at a normal number (at least 2.225074e-308; "
            "responses are relative, any scale above that is normalised), found a peak of "
            "1e-310");
}

} // namespace
} // namespace nx

namespace nx {
namespace {

// A measured band named by a wavelength keeps it as the name of its channel; other names get
// nominal centres given separately (withNominalCentres), which round-trip through toString.
TEST(Sensor, NominalCentresNameMeasuredBands) {
  const std::string csv = "nm,B1,B2\n440,0,0\n450,1,0\n470,0,0\n480,0,0\n500,0,1\n530,0,0\n";
  const Sensor plain = Sensor::fromCsv(csv, "srf.csv");
  EXPECT_EQ(plain.channelNm(0), plain.centroid(0)); // "B1" is no wavelength
  const Sensor named = plain.withNominalCentres("450,500", "centres");
  EXPECT_EQ(named.channelNm(0), 450);
  EXPECT_EQ(named.channelNm(1), 500);
  EXPECT_EQ(named.centroid(1), plain.centroid(1)); // the responses are unchanged
  EXPECT_NE(named.centroid(1), 500);
  EXPECT_EQ(Sensor::parse(named.toString()).channelNm(1), 500);
  for (const char* name : {"650", "650nm", "650 nm", " 650.5 NM"}) {
    SensorChannel c;
    c.shape = ResponseShape::Table;
    c.name = name;
    ASSERT_TRUE(c.nominalNm()) << name;
  }
  SensorChannel box;
  box.name = "650"; // a box is named at its centre whatever its name
  EXPECT_FALSE(box.nominalNm());
  EXPECT_NE(test::errorMessage([&] {
              plain.withNominalCentres("450", "t.scn:3");
            }).find("t.scn:3: expected 2 nominal centres (one per band of the sensor), found 1"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([] {
              Sensor(SpectralBands::parse("400:500:50")).withNominalCentres("1,2,3", "w");
            }).find("expected nominal centres for measured responses"),
            std::string::npos);
}

} // namespace
} // namespace nx
