#include "io/srgb_image.h"

#include <array>
#include <climits>
#include <memory>

#include "core/error.h"
#include "core/memory.h"
#include "spectra/colour.h"

// Static functions: this file's copy of stb_image does not clash with another one linked in.
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_NO_STDIO
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#endif
#include <stb/stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace nx {
namespace {

// Width, height (big-endian at bytes 16 and 20) and samples per pixel (from the colour type
// at byte 25) of a PNG's IHDR chunk, for messages
// about images stb_image refuses to size.
bool pngHeaderSize(const std::string& b, unsigned long& w, unsigned long& h, int& samples) {
  if (b.size() < 26 || b.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0 || b.compare(12, 4, "IHDR") != 0)
    return false;
  auto be32 = [&](size_t at) {
    unsigned long v = 0;
    for (size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(b[at + i]);
    return v;
  };
  w = be32(16);
  h = be32(20);
  const int colourType = static_cast<unsigned char>(b[25]);
  samples = colourType == 2 || colourType == 3 ? 3 : colourType == 4 ? 2 : colourType == 6 ? 4 : 1;
  return true;
}

std::string decodeFailure(const std::string& path) {
  const char* why = stbi_failure_reason();
  return path + ": cannot decode the image: its data is corrupt or cut short" +
         (why && *why ? " (" + std::string(why) + ")" : std::string());
}

} // namespace

namespace {

// Size and depth of the image in `bytes`, checked: a PNG or JPEG that stb_image can size and
// whose buffers (`bytesPerTexel` each) fit in memory.
struct ImageHeader {
  int width = 0, height = 0, channels = 0;
  bool sixteen = false;
};

ImageHeader checkedHeader(const std::string& bytes, const std::string& path, double bytesPerTexel) {
  if (bytes.size() > static_cast<size_t>(INT_MAX))
    throw Error(path + ": expected an image file below 2 GiB, found " +
                std::to_string(bytes.size()) + " bytes");
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = static_cast<int>(bytes.size());
  ImageHeader h;
  if (!stbi_info_from_memory(data, size, &h.width, &h.height, &h.channels)) {
    if (bytes.empty()) throw Error(path + ": expected a PNG or JPEG image, found an empty file");
    unsigned long pw = 0, ph = 0;
    int samples = 1;
    if (pngHeaderSize(bytes, pw, ph, samples) &&
        static_cast<double>(pw) * static_cast<double>(ph) * samples > 1073741824.0)
      throw Error(path + ": expected a PNG of at most 2^30 samples (stb_image's limit), found " +
                  std::to_string(pw) + " x " + std::to_string(ph) + " pixels");
    throw Error(path + ": expected a PNG or JPEG image, found data stb_image cannot read (" +
                std::string(stbi_failure_reason()) + ")");
  }
  if (h.width <= 0 || h.height <= 0)
    throw Error(path + ": expected an image of at least 1 x 1 pixels, found " +
                std::to_string(h.width) + " x " + std::to_string(h.height));
  h.sixteen = stbi_is_16_bit_from_memory(data, size) != 0;
  requireMemory(static_cast<double>(h.width) * h.height * bytesPerTexel, path, "an image",
                std::to_string(h.width) + " x " + std::to_string(h.height) + " pixels");
  return h;
}

} // namespace

LinearSrgbImage decodeSrgbImage(const std::string& bytes, const std::string& path) {
  // Decoded samples (at most 6 bytes), the linear floats and a texture's three coefficients.
  const ImageHeader header = checkedHeader(bytes, path, 6.0 + 12.0 + 12.0);
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = static_cast<int>(bytes.size());
  const int w = header.width, h = header.height, channels = header.channels;
  const bool sixteen = header.sixteen;
  LinearSrgbImage img;
  img.width = w;
  img.height = h;
  img.bitsPerChannel = sixteen ? 16 : 8;
  img.hadAlpha = channels == 2 || channels == 4;
  const size_t count = static_cast<size_t>(w) * static_cast<size_t>(h) * 3;
  img.rgb.resize(count);
  int gotW = 0, gotH = 0, gotChannels = 0;
  if (sixteen) {
    std::unique_ptr<stbi_us, void (*)(void*)> px(
        stbi_load_16_from_memory(data, size, &gotW, &gotH, &gotChannels, 3), stbi_image_free);
    if (!px || gotW != w || gotH != h) throw Error(decodeFailure(path));
    for (size_t i = 0; i < count; ++i)
      img.rgb[i] = static_cast<float>(srgbDecode(px.get()[i] / 65535.0));
  } else {
    std::unique_ptr<stbi_uc, void (*)(void*)> px(
        stbi_load_from_memory(data, size, &gotW, &gotH, &gotChannels, 3), stbi_image_free);
    if (!px || gotW != w || gotH != h) throw Error(decodeFailure(path));
    std::array<float, 256> decode{};
    for (int v = 0; v < 256; ++v) decode[v] = static_cast<float>(srgbDecode(v / 255.0));
    for (size_t i = 0; i < count; ++i) img.rgb[i] = decode[px.get()[i]];
  }
  return img;
}

GreyImage decodeGreyImage(const std::string& bytes, const std::string& path) {
  const ImageHeader header = checkedHeader(bytes, path, 2.0 + 4.0);
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = static_cast<int>(bytes.size());
  GreyImage img;
  img.width = header.width;
  img.height = header.height;
  img.bitsPerChannel = header.sixteen ? 16 : 8;
  const size_t count = static_cast<size_t>(img.width) * static_cast<size_t>(img.height);
  img.value.resize(count);
  int gotW = 0, gotH = 0, gotChannels = 0;
  if (header.sixteen) {
    std::unique_ptr<stbi_us, void (*)(void*)> px(
        stbi_load_16_from_memory(data, size, &gotW, &gotH, &gotChannels, 1), stbi_image_free);
    if (!px || gotW != img.width || gotH != img.height) throw Error(decodeFailure(path));
    for (size_t i = 0; i < count; ++i) img.value[i] = px.get()[i];
  } else {
    std::unique_ptr<stbi_uc, void (*)(void*)> px(
        stbi_load_from_memory(data, size, &gotW, &gotH, &gotChannels, 1), stbi_image_free);
    if (!px || gotW != img.width || gotH != img.height) throw Error(decodeFailure(path));
    for (size_t i = 0; i < count; ++i) img.value[i] = px.get()[i];
  }
  return img;
}

} // namespace nx
