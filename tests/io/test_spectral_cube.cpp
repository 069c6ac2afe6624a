// Spectral cubes: ENVI in every interleave, data type and byte order (files written here byte
// by byte), TIFF with band wavelengths, per-band PNG stacks, spectral EXR, and the errors of
// malformed cubes.

#include <gdal.h>
#include <gdal_frmts.h>
#include <gtest/gtest.h>
#include <stb/stb_image_write.h>
#include <sys/stat.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "io/float_tiff.h"
#include "io/spectral_cube.h"
#include "io/spectral_exr.h"
#include "support/errors.h"

namespace nx {
namespace {

constexpr int W = 3, H = 2, B = 4;

// The test value of sample (x, y, band).
double value(int x, int y, int b) {
  return b * 6 + y * 3 + x + 1;
}

std::string dir() {
  const std::string d = ::testing::TempDir() + "/cubes";
  std::filesystem::create_directories(d);
  return d;
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Appends v as ENVI data type `type` in the given byte order.
void appendValue(std::string& out, double v, int type, bool bigEndian) {
  unsigned char bytes[8];
  size_t n = 0;
  auto put = [&](const auto& x) {
    n = sizeof x;
    std::memcpy(bytes, &x, n);
  };
  switch (type) {
  case 1:
    put(static_cast<uint8_t>(v));
    break;
  case 2:
    put(static_cast<int16_t>(v));
    break;
  case 3:
    put(static_cast<int32_t>(v));
    break;
  case 4:
    put(static_cast<float>(v));
    break;
  case 5:
    put(v);
    break;
  case 12:
    put(static_cast<uint16_t>(v));
    break;
  case 13:
    put(static_cast<uint32_t>(v));
    break;
  default:
    FAIL() << "type " << type;
  }
  if (bigEndian) std::reverse(bytes, bytes + n);
  out.append(reinterpret_cast<const char*>(bytes), n);
}

std::string enviCube(const std::string& name, const std::string& interleave, int type,
                     bool bigEndian, const std::string& extraHeader) {
  std::string data;
  auto at = [&](int x, int y, int b) { appendValue(data, value(x, y, b), type, bigEndian); };
  if (interleave == "bsq")
    for (int b = 0; b < B; ++b)
      for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) at(x, y, b);
  else if (interleave == "bil")
    for (int y = 0; y < H; ++y)
      for (int b = 0; b < B; ++b)
        for (int x = 0; x < W; ++x) at(x, y, b);
  else
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x)
        for (int b = 0; b < B; ++b) at(x, y, b);
  const std::string base = dir() + "/" + name;
  writeText(base + ".img", data);
  writeText(base + ".hdr", "ENVI\nsamples = 3\nlines = 2\nbands = 4\nheader offset = 0\n"
                           "file type = ENVI Standard\ndata type = " +
                               std::to_string(type) + "\ninterleave = " + interleave +
                               "\nbyte order = " + (bigEndian ? "1" : "0") + "\n" + extraHeader);
  return base;
}

const std::string kWavelengths =
    "wavelength units = Nanometers\nwavelength = {450, 500.5, 550, 600}\nfwhm = {10, 10, 12, 12}\n";

void expectTestValues(const SpectralCube& c) {
  ASSERT_EQ(c.width, W);
  ASSERT_EQ(c.height, H);
  ASSERT_EQ(c.bands(), B);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      for (int b = 0; b < B; ++b)
        EXPECT_EQ(c.values[static_cast<size_t>((y * W + x) * B + b)], value(x, y, b))
            << x << "," << y << " band " << b;
}

TEST(SpectralCube, EnviInEveryInterleaveTypeAndByteOrder) {
  for (const std::string il : {"bsq", "bil", "bip"})
    for (int type : {1, 2, 3, 4, 5, 12, 13})
      for (bool big : {false, true}) {
        SCOPED_TRACE(il + " type " + std::to_string(type) + (big ? " big-endian" : ""));
        const std::string base =
            enviCube(il + std::to_string(type) + (big ? "b" : "l"), il, type, big, kWavelengths);
        const SpectralCube byHeader = readSpectralCube(base + ".hdr");
        expectTestValues(byHeader);
        EXPECT_EQ(byHeader.wavelengthNm, (std::vector<double>{450, 500.5, 550, 600}));
        EXPECT_EQ(byHeader.fwhmNm, (std::vector<double>{10, 10, 12, 12}));
        expectTestValues(readSpectralCube(base + ".img")); // named by its data file
      }
}

TEST(SpectralCube, MicrometresAndCommandLineWavelengths) {
  const std::string um =
      enviCube("um", "bsq", 4, false,
               "wavelength units = Micrometers\nwavelength = {0.45, 0.5, 0.55, 0.6}\n");
  const SpectralCube c = readSpectralCube(um + ".hdr");
  EXPECT_NEAR(c.wavelengthNm[1], 500, 1e-9);
  EXPECT_TRUE(c.fwhmNm.empty());
  const std::string none = enviCube("nowl", "bsq", 4, false, "");
  CubeReadOptions o;
  o.wavelengthNm = {400, 410, 420, 430};
  o.fwhmNm = {5};
  const SpectralCube d = readSpectralCube(none + ".hdr", o);
  EXPECT_EQ(d.wavelengthNm[3], 430);
  EXPECT_EQ(d.fwhmNm, (std::vector<double>(4, 5.0)));
}

TEST(SpectralCube, MalformedEnviCubesNameTheFileAndTheProblem) {
  const std::string none = enviCube("nowl2", "bsq", 4, false, "");
  EXPECT_NE(test::errorMessage([&] { readSpectralCube(none + ".hdr"); })
                .find("nowl2.hdr: expected a wavelength list ('wavelength = {...}' in the ENVI "
                      "header, or --capture-wavelengths), found none"),
            std::string::npos);
  const std::string cut = enviCube("cut", "bil", 2, false, kWavelengths);
  std::filesystem::resize_file(cut + ".img", 40);
  EXPECT_NE(test::errorMessage([&] { readSpectralCube(cut + ".hdr"); })
                .find("cut.img: expected 48 bytes (header offset + 3 x 2 x 4 Int16 values), found "
                      "40: the data file is cut short"),
            std::string::npos);
  const std::string lonely = dir() + "/lonely.hdr";
  writeText(lonely, "ENVI\nsamples = 3\n");
  EXPECT_NE(test::errorMessage([&] {
              readSpectralCube(lonely);
            }).find("lonely.hdr: expected the ENVI data file beside the header"),
            std::string::npos);
  const std::string wrongCount =
      enviCube("count", "bsq", 4, false, "wavelength = {450, 500, 550}\n");
  EXPECT_NE(test::errorMessage([&] {
              readSpectralCube(wrongCount + ".hdr");
            }).find("expected 4 wavelengths (one per band), found 3"),
            std::string::npos);
  const std::string decreasing =
      enviCube("decr", "bsq", 4, false, "wavelength = {450, 500, 490, 600}\n");
  EXPECT_NE(test::errorMessage([&] {
              readSpectralCube(decreasing + ".hdr");
            }).find("expected increasing band wavelengths, found 500 nm then 490 nm"),
            std::string::npos);
  EXPECT_NE(
      test::errorMessage([&] { readSpectralCube(dir() + "/absent.hdr"); }).find("does not exist"),
      std::string::npos);
  writeText(dir() + "/notes.txt", "hello");
  EXPECT_NE(test::errorMessage([&] {
              readSpectralCube(dir() + "/notes.txt");
            }).find("expected a spectral EXR (.exr), an ENVI cube"),
            std::string::npos);
}

// ENVI layout fields GDAL does not know were read as its defaults (interleave xyz as BSQ, byte
// order 7 as big-endian); an absurd header offset overflowed the size message.
TEST(SpectralCube, EnviLayoutFieldsAreCheckedBeforeGdal) {
  const std::pair<std::string, std::string> cases[] = {
      {"interleave = xyz\n", ":13: expected 'interleave' bsq, bil or bip, found 'xyz'"},
      {"byte order = 7\n",
       ":13: expected 'byte order' 0 (little-endian) or 1 (big-endian), found '7'"},
      {"data type = 6\n", ":13: expected a real 'data type' (1 byte, 2 int16, 3 int32, 4 float32, "
                          "5 float64, 12 uint16, 13 uint32, 14 int64, 15 uint64), found '6'"},
      {"header offset = 1e300\n",
       ":13: expected 'header offset' as a whole number from 0 to 96 (the data file's size in "
       "bytes), found 1e300"},
      {"samples = 2.5\n", ":13: expected 'samples' as a whole number from 1 to 2147483647, "
                          "found 2.5"},
      {"interleave = {bsq\n", ":13: expected the closing brace of 'interleave', found the end of "
                              "the header"},
  };
  int i = 0;
  for (const auto& [extra, message] : cases) {
    const std::string base =
        enviCube("layout" + std::to_string(i++), "bsq", 4, false, kWavelengths + extra);
    EXPECT_EQ(test::errorMessage([&] { readSpectralCube(base + ".hdr"); }),
              base + ".hdr" + message);
  }
}

// Inputs a library opens itself reach it only as regular files: a FIFO blocked GDAL and
// OpenEXR forever.
TEST(SpectralCube, FifosAreRefusedUnread) {
  const std::string fifoExr = dir() + "/fifo.exr", fifoTif = dir() + "/fifo.tif";
  for (const std::string& f : {fifoExr, fifoTif}) {
    std::filesystem::remove(f);
    ASSERT_EQ(mkfifo(f.c_str(), 0600), 0);
  }
  EXPECT_EQ(test::errorMessage([&] { readSpectralCube(fifoExr); }),
            fifoExr + ": expected an EXR file (a regular file), found a FIFO, socket or device");
  EXPECT_EQ(test::errorMessage([&] { readSpectralExr(fifoExr); }),
            fifoExr + ": expected an EXR file (a regular file), found a FIFO, socket or device");
  EXPECT_EQ(test::errorMessage([&] { spectralExrFootprint(fifoExr); }),
            fifoExr + ": expected an EXR file (a regular file), found a FIFO, socket or device");
  EXPECT_EQ(test::errorMessage([&] { readSpectralCube(fifoTif); }),
            fifoTif + ": expected a TIFF file (a regular file), found a FIFO, socket or device");
  // An ENVI cube whose data file or header is a FIFO.
  const std::string base = enviCube("fifodata", "bsq", 4, false, kWavelengths);
  std::filesystem::remove(base + ".img");
  ASSERT_EQ(mkfifo((base + ".img").c_str(), 0600), 0);
  EXPECT_EQ(test::errorMessage([&] { readSpectralCube(base + ".hdr"); }),
            base + ".img: expected an ENVI data file (a regular file), found a FIFO, socket or "
                   "device");
  const std::string base2 = enviCube("fifohdr", "bsq", 4, false, kWavelengths);
  std::filesystem::remove(base2 + ".hdr");
  ASSERT_EQ(mkfifo((base2 + ".hdr").c_str(), 0600), 0);
  EXPECT_EQ(test::errorMessage([&] { readSpectralCube(base2 + ".img"); }),
            base2 +
                ".hdr: expected an ENVI header (a regular file), found a FIFO, socket or device");
  for (const std::string& f : {fifoExr, fifoTif, base + ".img", base2 + ".hdr"})
    std::filesystem::remove(f);
}

TEST(SpectralCube, MultiBandTiffWithBandWavelengths) {
  GDALRegister_GTiff();
  const std::string path = dir() + "/cube.tif";
  GDALDatasetH ds =
      GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), W, H, B, GDT_UInt16, nullptr);
  ASSERT_TRUE(ds);
  for (int b = 0; b < B; ++b) {
    std::vector<uint16_t> plane;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) plane.push_back(static_cast<uint16_t>(value(x, y, b)));
    GDALRasterBandH band = GDALGetRasterBand(ds, b + 1);
    ASSERT_EQ(GDALRasterIO(band, GF_Write, 0, 0, W, H, plane.data(), W, H, GDT_UInt16, 0, 0),
              CE_None);
    GDALSetMetadataItem(band, "wavelength", std::to_string(400 + 10 * b).c_str(), nullptr);
    GDALSetMetadataItem(band, "wavelength_units", "nm", nullptr);
  }
  GDALClose(ds);
  const SpectralCube c = readSpectralCube(path);
  expectTestValues(c);
  EXPECT_EQ(c.wavelengthNm, (std::vector<double>{400, 410, 420, 430}));
}

TEST(SpectralCube, SpectralExrKeepsBandsVarianceAndIds) {
  SpectralImage img;
  img.width = 2;
  img.height = 1;
  img.bands = Sensor(SpectralBands::parse("500:600:50"));
  img.radiance = {1, 2, 3, 4, 5, 6};
  img.rgb.assign(6, 0.5f);
  img.bandVariance = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f};
  img.objectId = {3, 7};
  img.attributes["nxrender.bands"] = img.bands.toString();
  const std::string path = dir() + "/r.exr";
  writeSpectralExr(path, img);
  const SpectralCube c = readSpectralCube(path);
  EXPECT_EQ(c.format, "spectral EXR");
  EXPECT_EQ(c.bands(), 3);
  EXPECT_EQ(c.values, img.radiance);
  EXPECT_EQ(c.variance, img.bandVariance);
  EXPECT_EQ(c.objectId, img.objectId);
}

// A CAVE-style stack: one grey PNG per band, named so that only a natural sort gets the
// order right (s_1, s_2, s_3, s_10).
TEST(SpectralCube, PngStackInNaturalOrder) {
  const std::string stack = dir() + "/stack";
  std::filesystem::remove_all(stack); // a fresh stack on every run
  std::filesystem::create_directories(stack);
  const int numbers[B] = {1, 2, 3, 10};
  for (int b = 0; b < B; ++b) {
    std::vector<unsigned char> px;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) px.push_back(static_cast<unsigned char>(value(x, y, b)));
    const std::string name = stack + "/s_" + std::to_string(numbers[b]) + ".png";
    ASSERT_TRUE(stbi_write_png(name.c_str(), W, H, 1, px.data(), W));
  }
  CubeReadOptions o;
  o.wavelengthNm = {400, 410, 420, 430};
  const SpectralCube c = readSpectralCube(stack, o);
  expectTestValues(c);
  EXPECT_EQ(c.format, "PNG stack (4 8-bit files)");
  EXPECT_NE(test::errorMessage([&] {
              readSpectralCube(stack);
            }).find("stack: expected --capture-wavelengths for a stack of 4 per-band PNGs"),
            std::string::npos);
  o.wavelengthNm = {400, 410};
  EXPECT_NE(test::errorMessage([&] {
              readSpectralCube(stack, o);
            }).find("expected 4 wavelengths (one per PNG file), found 2"),
            std::string::npos);
  const std::vector<unsigned char> small(4, 0);
  ASSERT_TRUE(stbi_write_png((stack + "/s_11.png").c_str(), 2, 2, 1, small.data(), 2));
  o.wavelengthNm = {400, 410, 420, 430, 440};
  EXPECT_NE(test::errorMessage([&] {
              readSpectralCube(stack, o);
            }).find("s_11.png: expected 3 x 2 pixels like s_1.png, found 2 x 2"),
            std::string::npos);
}

// A map written as a float TIFF reads back through GDAL with its values and NaN no-data.
TEST(FloatTiff, MapReadsBack) {
  const std::string path = dir() + "/map.tif";
  writeFloatTiff(path, 3, 2, {0.5f, 1.5f, NAN, 3, 4, 5}, "angles");
  GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
  ASSERT_TRUE(ds);
  float v[6];
  ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Read, 0, 0, 3, 2, v, 3, 2, GDT_Float32, 0, 0),
            CE_None);
  int hasNoData = 0;
  EXPECT_TRUE(std::isnan(GDALGetRasterNoDataValue(GDALGetRasterBand(ds, 1), &hasNoData)));
  EXPECT_TRUE(hasNoData);
  GDALClose(ds);
  EXPECT_EQ(v[1], 1.5f);
  EXPECT_TRUE(std::isnan(v[2]));
  EXPECT_EQ(v[5], 5.0f);
  EXPECT_THROW(writeFloatTiff(path, 3, 3, {1, 2}, "short"), Error);
}

} // namespace
} // namespace nx
