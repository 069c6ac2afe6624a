#include <gtest/gtest.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>

#include "core/error.h"
#include "io/camera_attributes.h"
#include "io/exr_write_cost.h"
#include "io/spectral_exr.h"
#include "support/errors.h"

namespace nx {
namespace {

SpectralImage testImage() {
  SpectralImage img;
  img.width = 5;
  img.height = 3;
  img.bands = SpectralBands::parse("450:650:50");
  const int nb = img.bands.count();
  for (int p = 0; p < 15; ++p) {
    for (int b = 0; b < nb; ++b) img.radiance.push_back(0.25f * float(p) + float(b) + 0.125f);
    for (int c = 0; c < 3; ++c) img.rgb.push_back(0.5f * float(p) + float(c));
  }
  img.attributes["nxrender.scene"] = "scenes/test.scn";
  img.attributes["nxrender.spp"] = "16";
  return img;
}

TEST(SpectralExr, ChannelNamesFollowTheLayout) {
  EXPECT_EQ(spectralChannelName(550), "S0.550,000000nm");
  EXPECT_EQ(spectralChannelName(402.5), "S0.402,500000nm");
  // The reference reader's regular expression (Fichet et al. 2021).
  const std::regex ref(
      R"(^((S([0-3]))|T)\.(\d*,?\d*([Ee][+-]?\d+)?)(Y|Z|E|P|T|G|M|k|h|da|d|c|m|u|n|p)?(m|Hz)$)");
  EXPECT_TRUE(std::regex_match(spectralChannelName(700), ref));
  EXPECT_FALSE(std::regex_match(std::string("R"), ref));
}

// The channels a file of an image's shape holds are known before the image exists (the
// memory check before a render counts its writer): exactly those written, for every optional
// part.
TEST(SpectralExr, ChannelCountOfAShapeIsTheFilesCount) {
  const std::string path = ::testing::TempDir() + "channels.exr";
  auto channelsIn = [&](const SpectralImage& img) {
    writeSpectralExr(path, img);
    Imf::InputFile in(path.c_str());
    size_t n = 0;
    for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it) ++n;
    return n;
  };
  SpectralImage img = testImage();
  const size_t pixels = 15, nb = static_cast<size_t>(img.bands.count());
  EXPECT_EQ(exrChannelCount(shapeOf(img)), channelsIn(img));
  img.xyz.assign(pixels * 3, 0.1f);
  img.bandVariance.assign(pixels * nb, 0.01f);
  img.yVariance.assign(pixels, 0.01f);
  img.sampleCount.assign(pixels, 4);
  EXPECT_EQ(exrChannelCount(shapeOf(img)), channelsIn(img));
  img.white.assign(pixels * nb, 1.0f);
  img.objectId.assign(pixels, 1);
  img.materialId.assign(pixels, 2);
  img.depth.assign(pixels, 3.0f);
  for (const char* name : {"reflected", "light.lamp"})
    img.layers.push_back(
        {name, std::vector<float>(pixels * nb, 0.5f), std::vector<float>(pixels * nb, 0.01f)});
  EXPECT_EQ(exrChannelCount(shapeOf(img)), channelsIn(img));
  for (ImageLayer& l : img.layers) l.variances.clear();
  EXPECT_EQ(exrChannelCount(shapeOf(img)), channelsIn(img));
  // The writer's buffers grow with the channels and with the compression's chunk of lines.
  const ExrImageShape shape = shapeOf(img);
  ExrEncoding none, zip;
  zip.compression = ExrCompression::Zip;
  EXPECT_GT(exrWriteBytes(shape, zip, false), exrWriteBytes(shape, none, false));
  ExrImageShape more = shape;
  more.layers *= 10;
  EXPECT_GT(exrWriteBytes(more, none, false), exrWriteBytes(shape, none, false));
}

TEST(SpectralExr, RoundTripThroughOpenExr) {
  const SpectralImage img = testImage();
  const std::string path = ::testing::TempDir() + "roundtrip.exr";
  writeSpectralExr(path, img);

  Imf::InputFile in(path.c_str());
  const Imf::Header& h = in.header();
  EXPECT_EQ(h.typedAttribute<Imf::StringAttribute>("spectralLayoutVersion").value(), "1.0");
  EXPECT_EQ(h.typedAttribute<Imf::StringAttribute>("emissiveUnits").value(), "W.m^-2.sr^-1");
  EXPECT_EQ(h.typedAttribute<Imf::StringAttribute>("nxrender.scene").value(), "scenes/test.scn");
  EXPECT_EQ(h.typedAttribute<Imf::StringAttribute>("nxrender.spp").value(), "16");
  const auto dw = h.dataWindow();
  ASSERT_EQ(dw.max.x - dw.min.x + 1, 5);
  ASSERT_EQ(dw.max.y - dw.min.y + 1, 3);

  std::vector<std::string> names;
  for (auto it = h.channels().begin(); it != h.channels().end(); ++it) names.push_back(it.name());
  const std::vector<std::string> expected{"B",
                                          "G",
                                          "R",
                                          "S0.450,000000nm",
                                          "S0.500,000000nm",
                                          "S0.550,000000nm",
                                          "S0.600,000000nm",
                                          "S0.650,000000nm"};
  EXPECT_EQ(names, expected);

  const int nb = img.bands.count();
  std::vector<float> bands(15 * nb), rgb(15 * 3);
  Imf::FrameBuffer fb;
  for (int b = 0; b < nb; ++b)
    fb.insert(spectralChannelName(img.bands.centroid(b)),
              Imf::Slice(Imf::FLOAT, (char*)(bands.data() + b), sizeof(float) * nb,
                         sizeof(float) * nb * 5));
  const char* rgbNames[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c)
    fb.insert(rgbNames[c], Imf::Slice(Imf::FLOAT, (char*)(rgb.data() + c), 12, 60));
  in.setFrameBuffer(fb);
  in.readPixels(dw.min.y, dw.max.y);
  EXPECT_EQ(bands, img.radiance);
  EXPECT_EQ(rgb, img.rgb);
  // No temporary file is left behind.
  for (const auto& e : std::filesystem::directory_iterator(::testing::TempDir()))
    EXPECT_EQ(e.path().filename().string().find("roundtrip.exr.tmp"), std::string::npos);
}

// A measured sensor travels with the file: its responses are in nxrender.bands, the channels
// are named at the bands' centroids, and the reader rebuilds the same sensor (so nxmerge,
// nxdiff and --resume find the same channels).
TEST(SpectralExr, MeasuredSensorIsStoredInTheFile) {
  SpectralImage img = testImage();
  img.bands = Sensor::fromCsv("nm,blue,nir\n440,0,0\n450,1,0\n470,0,0\n900,0,0\n910,0.5,0\n"
                              "930,0,1\n931,0,0\n",
                              "srf.csv");
  // Band 0 is two triangles: 440-470 nm (peak 1 at 450; area 15, centroid (440+450+470)/3) and
  // 900-930 nm (peak 0.5 at 910; area 7.5, centroid (900+910+930)/3).
  const double c0 = (15 * (440 + 450 + 470) / 3.0 + 7.5 * (900 + 910 + 930) / 3.0) / 22.5;
  ASSERT_NEAR(img.bands.centroid(0), c0, 1e-9);
  img.radiance.clear();
  for (int p = 0; p < 15; ++p)
    for (int b = 0; b < 2; ++b) img.radiance.push_back(float(p) + 0.5f * float(b));
  img.attributes["nxrender.bands"] = img.bands.toString();
  const std::string path = ::testing::TempDir() + "measured.exr";
  writeSpectralExr(path, img);
  Imf::InputFile in(path.c_str());
  EXPECT_TRUE(in.header().channels().findChannel(spectralChannelName(img.bands.centroid(0))));
  EXPECT_TRUE(in.header().channels().findChannel(spectralChannelName(img.bands.centroid(1))));
  const SpectralImage back = readSpectralExr(path);
  ASSERT_EQ(back.bands.count(), 2);
  EXPECT_EQ(back.bands.toString(), img.bands.toString());
  EXPECT_EQ(back.bands.channel(1).name, "nir");
  EXPECT_EQ(back.bands.centroid(0), img.bands.centroid(0));
  EXPECT_EQ(back.radiance, img.radiance);
}

// A vendor SRF whose header names the bands by nominal centre ("450", "900 nm"): the channels
// keep those names however far a side lobe pulls the centroid, each band's name, centroid and
// FWHM are attributes, and a file written with channels at the centroids still reads.
TEST(SpectralExr, MeasuredBandsKeepTheirNominalCentres) {
  SpectralImage img = testImage();
  img.bands = Sensor::fromCsv("nm,450,900 nm\n440,0,0\n450,1,0\n470,0,0\n900,0,0\n910,0.5,0\n"
                              "930,0,1\n931,0,0\n",
                              "srf.csv");
  ASSERT_GT(std::abs(img.bands.centroid(0) - 450), 100); // the side lobe at 910 nm
  EXPECT_EQ(img.bands.channelNm(0), 450);
  EXPECT_EQ(img.bands.channelNm(1), 900);
  img.radiance.clear();
  for (int p = 0; p < 15; ++p)
    for (int b = 0; b < 2; ++b) img.radiance.push_back(float(p) + 0.5f * float(b));
  img.attributes["nxrender.bands"] = img.bands.toString();
  const std::string path = ::testing::TempDir() + "nominal.exr";
  writeSpectralExr(path, img);
  {
    Imf::InputFile in(path.c_str());
    EXPECT_TRUE(in.header().channels().findChannel("S0.450,000000nm"));
    EXPECT_TRUE(in.header().channels().findChannel("S0.900,000000nm"));
    const auto* names = in.header().findTypedAttribute<Imf::StringAttribute>("nxrender.bandNames");
    ASSERT_NE(names, nullptr);
    EXPECT_EQ(names->value(), "450,900 nm");
    const auto* c = in.header().findTypedAttribute<Imf::StringAttribute>("nxrender.bandCentroids");
    ASSERT_NE(c, nullptr);
    EXPECT_EQ(c->value(), exactNumberText(img.bands.centroid(0)) + "," +
                              exactNumberText(img.bands.centroid(1)));
    EXPECT_NE(in.header().findTypedAttribute<Imf::StringAttribute>("nxrender.bandFwhm"), nullptr);
  }
  const SpectralImage back = readSpectralExr(path);
  EXPECT_EQ(back.bands.toString(), img.bands.toString());
  EXPECT_EQ(back.radiance, img.radiance);
  EXPECT_EQ(back.attributes.count("nxrender.bandNames"), 0u); // derived again, not carried
  // An older file: channels at the centroids (bands named otherwise), the same bands attribute.
  SpectralImage old = img;
  old.bands = Sensor::fromCsv("nm,a,b\n440,0,0\n450,1,0\n470,0,0\n900,0,0\n910,0.5,0\n"
                              "930,0,1\n931,0,0\n",
                              "old.csv");
  const std::string oldPath = ::testing::TempDir() + "centroid_named.exr";
  writeSpectralExr(oldPath, old);
  const SpectralImage oldBack = readSpectralExr(oldPath);
  EXPECT_EQ(oldBack.bands.toString(), img.bands.toString());
  EXPECT_EQ(oldBack.radiance, img.radiance);
  // Two bands named at one wavelength would name one channel twice: refused.
  EXPECT_NE(test::errorMessage([] {
              Sensor::fromCsv("nm,450,450nm\n440,0,0\n450,1,1\n470,0,0\n", "dup.csv");
            }).find("expected bands with distinct nominal centres"),
            std::string::npos);
}

TEST(SpectralExr, UnwritablePathIsAClearErrorAndWritesNothing) {
  SpectralImage img = testImage();
  try {
    writeSpectralExr("/nonexistent-dir/out.exr", img);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("/nonexistent-dir/out.exr: cannot write the file", 0), 0u)
        << e.what();
  }
  img.radiance.pop_back();
  EXPECT_THROW(writeSpectralExr(::testing::TempDir() + "bad.exr", img), Error);
  EXPECT_FALSE(std::filesystem::exists(::testing::TempDir() + "bad.exr"));
}

// Half-float output reads back within half precision (2^-11 relative; 2^-24 absolute near
// zero, the smallest half), with sample counts exact; a value beyond 65504 is refused and
// nothing is written.
TEST(SpectralExr, HalfFloatOutput) {
  SpectralImage img = testImage();
  img.sampleCount.assign(15, 123456789u);
  img.radiance[3] = 1e-6f;
  const std::string path = ::testing::TempDir() + "half.exr";
  img.attributes["nxrender.bands"] = img.bands.toString();
  ASSERT_TRUE(fitsInHalf(img));
  writeSpectralExrHalf(path, img);
  const SpectralImage back = readSpectralExr(path);
  ASSERT_EQ(back.radiance.size(), img.radiance.size());
  for (size_t i = 0; i < img.radiance.size(); ++i)
    EXPECT_NEAR(back.radiance[i], img.radiance[i],
                std::max(std::abs(img.radiance[i]) * 0.00049, 6e-8))
        << i;
  EXPECT_EQ(back.sampleCount, img.sampleCount);
  img.rgb[7] = 70000.0f;
  EXPECT_FALSE(fitsInHalf(img));
  const std::string big = ::testing::TempDir() + "half_big.exr";
  std::filesystem::remove(big);
  EXPECT_THROW(writeSpectralExrHalf(big, img), Error);
  EXPECT_FALSE(std::filesystem::exists(big));
}

// Every compression method writes a file OpenEXR reads back with the method in its header;
// the lossless ones return the bands bit for bit; the defaults are none for floats and piz
// for halves; unknown names and zip levels are errors that write nothing.
TEST(SpectralExr, CompressionMethods) {
  SpectralImage img = testImage();
  img.attributes["nxrender.bands"] = img.bands.toString();
  img.radiance[2] = 0.1234567f; // a value that a 24-bit or half float would change
  for (ExrCompression c : allExrCompressions()) {
    const std::string path = ::testing::TempDir() + "compression_" + exrCompressionName(c) + ".exr";
    writeSpectralExr(path, img, ExrEncoding{c, 9});
    Imf::InputFile in(path.c_str());
    EXPECT_EQ(static_cast<int>(in.header().compression()), static_cast<int>(c))
        << exrCompressionName(c);
    const SpectralImage back = readSpectralExr(path);
    ASSERT_EQ(back.radiance.size(), img.radiance.size());
    bool exact = true;
    for (size_t i = 0; i < img.radiance.size(); ++i) {
      exact = exact && back.radiance[i] == img.radiance[i];
      EXPECT_NEAR(back.radiance[i], img.radiance[i], 1e-4 * std::abs(img.radiance[i]))
          << exrCompressionName(c) << " value " << i;
    }
    if (keepsFloatsExactly(c)) {
      EXPECT_TRUE(exact) << exrCompressionName(c);
    }
    EXPECT_EQ(parseExrCompression(exrCompressionName(c), "--compression"), c);
  }
  EXPECT_EQ(defaultExrCompression(false), ExrCompression::None);
  EXPECT_EQ(defaultExrCompression(true), ExrCompression::Piz);
  const std::string plain = ::testing::TempDir() + "compression_default.exr";
  writeSpectralExr(plain, img);
  EXPECT_EQ(Imf::InputFile(plain.c_str()).header().compression(), Imf::NO_COMPRESSION);
  writeSpectralExrHalf(plain, img);
  EXPECT_EQ(Imf::InputFile(plain.c_str()).header().compression(), Imf::PIZ_COMPRESSION);
  EXPECT_NE(test::errorMessage([] {
              parseExrCompression("zip2", "--compression");
            }).find("--compression: expected one of none, rle, zips, zip, piz"),
            std::string::npos);
  const std::string bad = ::testing::TempDir() + "compression_level.exr";
  std::filesystem::remove(bad);
  EXPECT_NE(test::errorMessage([&] {
              writeSpectralExr(bad, img, ExrEncoding{ExrCompression::Zip, 10});
            }).find("expected a zip level from 1 to 9, found 10"),
            std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(bad));
}

// An EXR made by another tool whose data window is not inside its display window (nxmerge
// read out of bounds on one), or whose sample counts are floats (a resume silently restarted
// from zero), is refused by the reader with what it found.
TEST(SpectralExr, DataWindowOutsideDisplayWindowAndFloatCountsAreRefused) {
  auto write = [](const std::string& path, Imath::Box2i display, Imath::Box2i data,
                  Imf::PixelType countType) {
    Imf::Header h(display, data);
    h.insert("nxrender.bands", Imf::StringAttribute("500:600:100"));
    for (const std::string& c : {spectralChannelName(500), spectralChannelName(600),
                                 std::string("R"), std::string("G"), std::string("B")})
      h.channels().insert(c, Imf::Channel(Imf::FLOAT));
    h.channels().insert(kSampleCountChannel, Imf::Channel(countType));
    const int w = data.max.x - data.min.x + 1, rows = data.max.y - data.min.y + 1;
    std::vector<float> zeros(static_cast<size_t>(w) * rows, 0.0f);
    Imf::FrameBuffer fb;
    fb.insert("R",
              Imf::Slice::Make(Imf::FLOAT, zeros.data(), data, sizeof(float), sizeof(float) * w));
    Imf::OutputFile f(path.c_str(), h);
    f.setFrameBuffer(fb); // the other channels are written as zeros
    f.writePixels(rows);
  };
  const std::string dir = ::testing::TempDir();
  write(dir + "outside.exr", {{0, 0}, {7, 5}}, {{6, 4}, {9, 7}}, Imf::UINT);
  EXPECT_EQ(test::errorMessage([&] { readSpectralExr(dir + "outside.exr"); }),
            dir + "outside.exr: expected a data window inside the display window 0,0-7,5, found "
                  "6,4-9,7");
  write(dir + "counts.exr", {{0, 0}, {7, 5}}, {{0, 0}, {7, 5}}, Imf::FLOAT);
  EXPECT_EQ(test::errorMessage([&] { readSpectralExr(dir + "counts.exr"); }),
            dir + "counts.exr: expected the SampleCount channel as 32-bit unsigned integers "
                  "(sample counts), found floats");
  write(dir + "fine.exr", {{0, 0}, {7, 5}}, {{2, 1}, {5, 3}}, Imf::UINT);
  const SpectralImage img = readSpectralExr(dir + "fine.exr");
  EXPECT_EQ(img.originX, 2);
  EXPECT_EQ(img.width, 4);
}

// The camera attributes give K, R, t and distortion exactly (they read back to the same
// doubles), and worldToCamera is [R t; 0 0 0 1].
TEST(CameraAttributes, ExactAndConsistent) {
  CameraCalibration c;
  c.fx = 812.123456789, c.fy = 790.5, c.cx = 331.7, c.cy = 251.2;
  c.R = {{{0.36, 0.48, -0.8}, {-0.8, 0.6, 0}, {0.48, 0.64, 0.6}}};
  c.t = Vec3d(0.1, -0.2, 4.5);
  c.distortion = {-0.21, 0.07, 0.0012, -0.0009, 0.013};
  PinholeCamera camera(c, 640, 480);
  EXPECT_EQ(cameraAttributes(camera).count("nxrender.camera.thinLens"), 0u);
  camera.setThinLens(0.025, 3.5);
  const auto a = cameraAttributes(camera);
  auto values = [&](const std::string& key) {
    std::vector<double> v;
    std::string text = a.at(key);
    size_t pos = 0;
    while (pos <= text.size()) {
      const size_t comma = std::min(text.find(',', pos), text.size());
      v.push_back(std::stod(text.substr(pos, comma - pos)));
      pos = comma + 1;
    }
    return v;
  };
  EXPECT_EQ(values("nxrender.camera.K"),
            (std::vector<double>{c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1}));
  EXPECT_EQ(values("nxrender.camera.t"), (std::vector<double>{0.1, -0.2, 4.5}));
  EXPECT_EQ(values("nxrender.camera.distortion")[4], 0.013);
  const auto w = values("nxrender.camera.worldToCamera");
  ASSERT_EQ(w.size(), 16u);
  EXPECT_EQ(w[2], -0.8);
  EXPECT_EQ(w[11], 4.5);
  EXPECT_EQ(w[15], 1.0);
  EXPECT_EQ(values("nxrender.camera.thinLens"), (std::vector<double>{0.025, 3.5}));
}

// An EXR declaring far more pixels than it holds (a 20 KB file declaring 40000 x 40000) is
// refused with the memory figures before any buffer is allocated (it ended in bad_alloc).
TEST(SpectralExr, HugeDeclaredImageIsRefusedBeforeAllocating) {
  const std::string path = ::testing::TempDir() + "huge_window.exr";
  {
    const Imath::Box2i window({0, 0}, {39999, 39999});
    Imf::Header h(window, window);
    h.compression() = Imf::ZIP_COMPRESSION;
    h.insert("nxrender.bands", Imf::StringAttribute("500:600:100"));
    for (const std::string& c : {spectralChannelName(500), spectralChannelName(600),
                                 std::string("R"), std::string("G"), std::string("B")})
      h.channels().insert(c, Imf::Channel(Imf::FLOAT));
    Imf::OutputFile f(path.c_str(), h); // the header and an empty offset table, no pixels
  }
  ASSERT_LT(std::filesystem::file_size(path), 1u << 20);
  const std::string message = test::errorMessage([&] { readSpectralExr(path); });
  EXPECT_EQ(message.rfind(path + ": expected an EXR whose buffers fit in memory, found 40000 x "
                                 "40000 pixels of 5 channels (needs 47.7 GiB; ",
                          0),
            0u)
      << message;
}

// A file whose bands attribute holds responses of 1e308 (the integrals overflowed: a NaN
// centroid named the channels, and every reader crashed on it) reads as the sensor it is.
TEST(SpectralExr, BandsOfAnyResponseScaleReadBackOrAreRefused) {
  SpectralImage img = testImage();
  img.bands = Sensor::parse("table:nm,a,b\n480,0,0\n500,1e308,0\n510,5e307,1e308\n520,0,0\n");
  const int nb = img.bands.count();
  img.radiance.assign(static_cast<size_t>(15 * nb), 1.0f);
  const std::string path = ::testing::TempDir() + "huge_responses.exr";
  writeSpectralExr(path, img);
  const SpectralImage back = readSpectralExr(path);
  ASSERT_EQ(back.bands.count(), 2);
  for (int b = 0; b < 2; ++b) EXPECT_NEAR(back.bands.centroid(b), img.bands.centroid(b), 1e-9);
  // A bands attribute that no sensor can be made of is an error naming the file.
  {
    const Imath::Box2i window({0, 0}, {0, 0});
    Imf::Header h(window, window);
    h.insert("nxrender.bands", Imf::StringAttribute("table:nm,a\n500,0\n510,nan\n520,0\n"));
    h.channels().insert("S0.510nm", Imf::Channel(Imf::FLOAT));
    Imf::OutputFile f((::testing::TempDir() + "nan_bands.exr").c_str(), h);
    float v = 0;
    Imf::FrameBuffer fb;
    fb.insert("S0.510nm", Imf::Slice::Make(Imf::FLOAT, &v, window, sizeof(float), sizeof(float)));
    f.setFrameBuffer(fb);
    f.writePixels(1);
  }
  EXPECT_NE(test::errorMessage([&] {
              readSpectralExr(::testing::TempDir() + "nan_bands.exr");
            }).find("nan_bands.exr: nxrender.bands"),
            std::string::npos);
}

// A NaN is named as a NaN, in float and half writes alike (the half writer said "found larger
// ones"), and nothing is written; an EXR is never written under another format's name.
TEST(SpectralExr, NonFiniteValuesAndForeignNamesAreRefused) {
  SpectralImage img = testImage();
  img.radiance[7] = std::nanf("");
  const std::string path = ::testing::TempDir() + "nan_value.exr";
  const std::string expected = path +
                               ": expected finite values in the spectral channels, found nan at "
                               "pixel 1,0 (nothing written)";
  EXPECT_EQ(test::errorMessage([&] { writeSpectralExr(path, img); }), expected);
  EXPECT_EQ(test::errorMessage([&] { writeSpectralExrHalf(path, img); }), expected);
  EXPECT_FALSE(std::filesystem::exists(path));
  const std::string png = ::testing::TempDir() + "image.png";
  EXPECT_EQ(test::errorMessage([&] { writeSpectralExr(png, testImage()); }),
            png +
                ": expected an output name ending in .exr (the file is an OpenEXR), found '.png'");
  EXPECT_FALSE(std::filesystem::exists(png));
}

// An attribute declaring more bytes than the file holds (OpenEXR allocated the 2 GB it
// declared, for 5 s) and a file that is not an EXR are refused before OpenEXR reads them.
TEST(SpectralExr, HeaderAttributesMustFitInTheFile) {
  const std::string path = ::testing::TempDir() + "attribute_size.exr";
  writeSpectralExr(path, testImage());
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const size_t at = bytes.find("compression");
  ASSERT_NE(at, std::string::npos);
  const size_t sizeAt =
      at + std::string("compression").size() + 1 + std::string("compression").size() + 1;
  const int32_t huge = 0x7ffffff0;
  std::memcpy(&bytes[sizeAt], &huge, 4);
  std::ofstream(path, std::ios::binary) << bytes;
  const std::string message = test::errorMessage([&] { readSpectralExr(path); });
  EXPECT_EQ(message.rfind(path +
                              ": expected header attribute 'compression' (compression) to fit in "
                              "the file, found a size of 2147483632 bytes",
                          0),
            0u)
      << message;
  // A channel list declared shorter than it is (OpenEXR reads a chlist to its end whatever
  // the size says, then read a 1.9 GB string out of the channels: fuzzing finding).
  writeSpectralExr(path, testImage());
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const size_t chlist = bytes.find("channels") + std::string("channels").size() + 1 + 7;
  int32_t chlistSize;
  std::memcpy(&chlistSize, &bytes[chlist], 4);
  const int32_t shorter = chlistSize - 18;
  std::memcpy(&bytes[chlist], &shorter, 4);
  std::ofstream(path, std::ios::binary) << bytes;
  EXPECT_EQ(test::errorMessage([&] { readSpectralExr(path); }),
            path + ": expected header attribute 'channels' (chlist) to fill its " +
                std::to_string(shorter) + " bytes exactly, found it malformed");
  std::ofstream(path, std::ios::binary) << "not an exr at all";
  EXPECT_EQ(test::errorMessage([&] { spectralExrFootprint(path); }),
            path + ": expected an OpenEXR file (magic number 76 2f 31 01), found other bytes");
}

} // namespace
} // namespace nx
