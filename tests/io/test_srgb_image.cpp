// Colour images decoded to linear sRGB: 8-bit PNG (RGB, RGBA, grey), 16-bit PNG, JPEG, and
// the errors for what is not such an image.

#include <gtest/gtest.h>
#include <stb/stb_image_write.h>

#include <fstream>
#include <sstream>

#include "core/error.h"
#include "io/srgb_image.h"
#include "spectra/colour.h"
#include "support/errors.h"

namespace nx {
namespace {

void appendBytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                             static_cast<size_t>(size));
}

std::string pngBytes(int w, int h, int channels, const std::vector<unsigned char>& px) {
  std::string out;
  stbi_write_png_to_func(appendBytes, &out, w, h, channels, px.data(), w * channels);
  return out;
}

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(SrgbImage, EightBitPngDecodesToLinearValues) {
  // 2 x 2 RGBA, row 0 at the top; alpha is read and ignored.
  const std::vector<unsigned char> px = {0,  128, 255, 10,  200, 100, 50,  255,
                                         30, 60,  90,  128, 255, 255, 255, 0};
  const LinearSrgbImage img = decodeSrgbImage(pngBytes(2, 2, 4, px), "a.png");
  ASSERT_EQ(img.width, 2);
  ASSERT_EQ(img.height, 2);
  EXPECT_EQ(img.bitsPerChannel, 8);
  EXPECT_TRUE(img.hadAlpha);
  for (int t = 0; t < 4; ++t)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(img.rgb[static_cast<size_t>(t * 3 + c)], srgbDecode(px[t * 4 + c] / 255.0), 1e-7)
          << "texel " << t << " channel " << c;
}

TEST(SrgbImage, GreyPngGivesEqualChannels) {
  const LinearSrgbImage img = decodeSrgbImage(pngBytes(3, 1, 1, {0, 64, 255}), "g.png");
  EXPECT_FALSE(img.hadAlpha);
  for (int t = 0; t < 3; ++t) {
    EXPECT_FLOAT_EQ(img.rgb[static_cast<size_t>(t * 3)], img.rgb[static_cast<size_t>(t * 3 + 1)]);
    EXPECT_FLOAT_EQ(img.rgb[static_cast<size_t>(t * 3)], img.rgb[static_cast<size_t>(t * 3 + 2)]);
  }
  EXPECT_NEAR(img.rgb[3], srgbDecode(64 / 255.0), 1e-7);
}

// tests/data/textures/rgb16.png: 2 x 1 pixels, 16-bit, (0, 32768, 65535) and
// (1000, 20000, 50000), written by OpenImageIO.
TEST(SrgbImage, SixteenBitPngKeepsItsPrecision) {
  const std::string path = std::string(NX_TEST_DATA_DIR) + "/textures/rgb16.png";
  const LinearSrgbImage img = decodeSrgbImage(fileBytes(path), path);
  ASSERT_EQ(img.width, 2);
  ASSERT_EQ(img.height, 1);
  EXPECT_EQ(img.bitsPerChannel, 16);
  const int values[6] = {0, 32768, 65535, 1000, 20000, 50000};
  for (int i = 0; i < 6; ++i)
    EXPECT_NEAR(img.rgb[static_cast<size_t>(i)], srgbDecode(values[i] / 65535.0), 1e-7);
}

TEST(SrgbImage, JpegDecodesNearItsColour) {
  std::vector<unsigned char> px(16 * 16 * 3);
  for (size_t i = 0; i < px.size(); i += 3) px[i] = 200, px[i + 1] = 120, px[i + 2] = 40;
  std::string jpg;
  stbi_write_jpg_to_func(appendBytes, &jpg, 16, 16, 3, px.data(), 100);
  const LinearSrgbImage img = decodeSrgbImage(jpg, "c.jpg");
  ASSERT_EQ(img.width, 16);
  // Quality 100 still rounds through YCbCr: within 3 code values.
  EXPECT_NEAR(img.rgb[0], srgbDecode(200 / 255.0),
              srgbDecode(203 / 255.0) - srgbDecode(200 / 255.0));
  EXPECT_NEAR(img.rgb[2], srgbDecode(40 / 255.0), srgbDecode(43 / 255.0) - srgbDecode(40 / 255.0));
}

TEST(SrgbImage, WhatIsNotAnImageIsRefusedWithItsPath) {
  EXPECT_NE(test::errorMessage([] {
              decodeSrgbImage("", "e.png");
            }).find("e.png: expected a PNG or JPEG image, found an empty file"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([] {
              decodeSrgbImage("wavelength,value\n400,0.5\n", "t.png");
            }).find("t.png: expected a PNG or JPEG image, found data stb_image cannot read"),
            std::string::npos);
  std::string png = pngBytes(2, 2, 3, std::vector<unsigned char>(12, 7));
  png.resize(png.size() - 20); // the image data cut short
  EXPECT_NE(test::errorMessage([&] { decodeSrgbImage(png, "cut.png"); }).find("cut.png: "),
            std::string::npos);
}

} // namespace
} // namespace nx
