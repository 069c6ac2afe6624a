#include "io/exr_header_check.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/error.h"
#include "io/exr_compression.h"

namespace nx {
namespace {

constexpr int kMaxAttributes = 100000;

// The NUL-terminated string at the stream's position, at most maxLength bytes before the NUL.
bool readName(std::ifstream& in, size_t maxLength, std::string& out) {
  out.clear();
  for (char c; in.get(c);) {
    if (c == '\0') return true;
    if (out.size() == maxLength) return false;
    out += c;
  }
  return false;
}

// The size an attribute of a standard type must have (OpenEXR reads these by their type,
// not by the size the file declares); -1 for types whose size is their own (string, opaque).
int64_t fixedSize(const std::string& type) {
  static const std::pair<const char*, int> kSizes[] = {{"box2i", 16},
                                                       {"box2f", 16},
                                                       {"compression", 1},
                                                       {"envmap", 1},
                                                       {"float", 4},
                                                       {"double", 8},
                                                       {"int", 4},
                                                       {"lineOrder", 1},
                                                       {"v2i", 8},
                                                       {"v2f", 8},
                                                       {"v2d", 16},
                                                       {"v3i", 12},
                                                       {"v3f", 12},
                                                       {"v3d", 24},
                                                       {"m33f", 36},
                                                       {"m33d", 72},
                                                       {"m44f", 64},
                                                       {"m44d", 128},
                                                       {"tiledesc", 9},
                                                       {"rational", 8},
                                                       {"timecode", 8},
                                                       {"keycode", 28},
                                                       {"chromaticities", 32},
                                                       {"deepImageState", 1}};
  for (const auto& [name, size] : kSizes)
    if (type == name) return size;
  return -1;
}

// True when `value` is a channel list that ends exactly at its end: channels of a name (NUL
// terminated, 1-255 bytes) and 16 bytes of type, flags and sampling, then an empty name.
// OpenEXR reads a chlist up to its empty name whatever the size says.
bool wellFormedChannelList(const std::string& value) {
  size_t p = 0;
  for (;;) {
    const size_t nul = value.find('\0', p);
    if (nul == std::string::npos || nul - p > 255) return false;
    if (nul == p) return nul + 1 == value.size();
    p = nul + 1 + 16;
    if (p > value.size()) return false;
  }
}

// True when `value` is a string vector whose strings fill it exactly (int32 length, bytes).
bool wellFormedStringVector(const std::string& value) {
  size_t p = 0;
  while (p < value.size()) {
    if (value.size() - p < 4) return false;
    int32_t n;
    std::memcpy(&n, value.data() + p, 4);
    p += 4;
    if (n < 0 || static_cast<size_t>(n) > value.size() - p) return false;
    p += static_cast<size_t>(n);
  }
  return true;
}

// True when `value` is a preview image: width and height (uint32), then 4 bytes per pixel,
// exactly (OpenEXR allocates the pixels the two numbers say).
bool wellFormedPreview(const std::string& value) {
  if (value.size() < 8) return false;
  uint32_t w, h;
  std::memcpy(&w, value.data(), 4);
  std::memcpy(&h, value.data() + 4, 4);
  return 8 + 4 * static_cast<uint64_t>(w) * h == value.size();
}

} // namespace

ExrHeaderSummary checkExrHeader(const std::string& path) {
  std::error_code ec;
  const auto fileSize = static_cast<uint64_t>(std::filesystem::file_size(path, ec));
  std::ifstream in(path, std::ios::binary);
  if (ec || !in) throw Error(path + ": cannot open the EXR file");
  unsigned char head[8] = {};
  in.read(reinterpret_cast<char*>(head), 8);
  if (!in || head[0] != 0x76 || head[1] != 0x2f || head[2] != 0x31 || head[3] != 0x01)
    throw Error(path + ": expected an OpenEXR file (magic number 76 2f 31 01), found other bytes");
  if (head[4] != 2)
    throw Error(path + ": expected OpenEXR file version 2, found " + std::to_string(head[4]));
  const bool multiPart = (head[5] & 0x10) != 0; // bit 12 of the version field
  ExrHeaderSummary summary;
  bool firstHeader = true, haveData = false, haveDisplay = false;
  std::vector<std::array<int32_t, 3>> channels; // type, x sampling, y sampling
  // What OpenEXR sizes its buffers by, checked once the first header is read.
  const auto finishFirstHeader = [&] {
    if (!haveData || !haveDisplay || channels.empty())
      throw Error(path +
                  ": expected a dataWindow, a displayWindow and channels in the EXR "
                  "header, found " +
                  std::string(!haveData      ? "no dataWindow"
                              : !haveDisplay ? "no displayWindow"
                                             : "no channels"));
    summary.channels = static_cast<int>(channels.size());
    for (const auto& [t, xs, ys] : channels) {
      if (t < 0 || t > 2 || xs < 1 || ys < 1)
        throw Error(path +
                    ": expected channels of type 0-2 (uint, half, float) with sampling "
                    ">= 1, found type " +
                    std::to_string(t) + " sampled " + std::to_string(xs) + " x " +
                    std::to_string(ys));
      summary.lineBytes +=
          std::ceil(static_cast<double>(summary.dataWidth) / xs) * (t == 1 ? 2 : 4);
    }
  };
  std::string name, type;
  int attributes = 0;
  for (;;) {
    if (!readName(in, 255, name))
      throw Error(path + ": expected header attribute names of at most 255 bytes ending in NUL, "
                         "found the header cut short or a longer name");
    if (name.empty()) { // the end of a header
      if (firstHeader) finishFirstHeader();
      firstHeader = false;
      if (!multiPart || in.peek() == 0) return summary; // an empty header ends the parts
      continue;
    }
    if (!readName(in, 255, type))
      throw Error(path + ": expected a type name after header attribute '" + name + "'");
    unsigned char sizeBytes[4];
    in.read(reinterpret_cast<char*>(sizeBytes), 4);
    const int64_t size = static_cast<int32_t>(
        static_cast<uint32_t>(sizeBytes[0]) | static_cast<uint32_t>(sizeBytes[1]) << 8 |
        static_cast<uint32_t>(sizeBytes[2]) << 16 | static_cast<uint32_t>(sizeBytes[3]) << 24);
    const auto at = static_cast<uint64_t>(in.tellg());
    if (!in || size < 0 || static_cast<uint64_t>(size) > fileSize - std::min(at, fileSize))
      throw Error(path + ": expected header attribute '" + name + "' (" + type +
                  ") to fit in the file, found a size of " + std::to_string(size) +
                  " bytes at byte " + std::to_string(at) + " of " + std::to_string(fileSize));
    if (++attributes > kMaxAttributes)
      throw Error(path + ": expected at most " + std::to_string(kMaxAttributes) +
                  " header attributes, found more");
    const int64_t fixed = fixedSize(type);
    if (fixed >= 0 && size != fixed)
      throw Error(path + ": expected header attribute '" + name + "' (" + type + ") of " +
                  std::to_string(fixed) + " bytes, found " + std::to_string(size));
    const bool sizing = firstHeader && ((name == "dataWindow" && type == "box2i") ||
                                        (name == "displayWindow" && type == "box2i") ||
                                        (name == "compression" && type == "compression") ||
                                        (name == "channels" && type == "chlist"));
    if (!sizing && type != "chlist" && type != "stringvector" && type != "preview") {
      in.seekg(size, std::ios::cur);
      continue;
    }
    std::string value(static_cast<size_t>(size), '\0');
    in.read(value.data(), size);
    if (!in || !(type == "chlist"         ? wellFormedChannelList(value)
                 : type == "stringvector" ? wellFormedStringVector(value)
                 : type == "preview"      ? wellFormedPreview(value)
                                          : true))
      throw Error(path + ": expected header attribute '" + name + "' (" + type + ") to fill its " +
                  std::to_string(size) + " bytes exactly, found it malformed");
    if (!sizing) continue;
    if (type == "chlist") { // well formed: names, then 16 bytes each
      channels.clear();
      for (size_t p = 0; value[p] != '\0';) {
        p = value.find('\0', p) + 1;
        int32_t v[4]; // type, pLinear and reserved bytes, x sampling, y sampling
        std::memcpy(v, value.data() + p, 16);
        channels.push_back({v[0], v[2], v[3]});
        p += 16;
      }
    } else if (type == "box2i") {
      int32_t b[4]; // min x, min y, max x, max y
      std::memcpy(b, value.data(), 16);
      const int64_t w = static_cast<int64_t>(b[2]) - b[0] + 1,
                    h = static_cast<int64_t>(b[3]) - b[1] + 1;
      if (w < 1 || h < 1)
        throw Error(path + ": expected a non-empty " + name + ", found " + std::to_string(b[0]) +
                    "," + std::to_string(b[1]) + "-" + std::to_string(b[2]) + "," +
                    std::to_string(b[3]));
      const bool data = name == "dataWindow";
      (data ? summary.dataWidth : summary.displayWidth) = w;
      (data ? summary.dataHeight : summary.displayHeight) = h;
      (data ? haveData : haveDisplay) = true;
    } else { // compression
      const auto c = static_cast<unsigned char>(value[0]);
      if (c > 9)
        throw Error(path + ": expected a compression method 0-9, found " + std::to_string(c));
      summary.chunkLines = exrChunkLines(static_cast<ExrCompression>(c));
    }
  }
}

} // namespace nx
