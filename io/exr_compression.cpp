#include "io/exr_compression.h"

#include <cstddef>
#include <iterator>

#include "core/error.h"

namespace nx {

namespace {

// Each method's name, whether it stores float channels bit for bit, the scan lines of its
// chunks (the file format's) and the buffers its OpenEXR compressor allocates in multiples of
// a chunk's raw bytes (ImfZipCompressor: a temporary and an output bound; RLE's output is
// 1.5 times; DWA keeps several planes), in the enum's order.
struct MethodInfo {
  ExrCompression method;
  const char* name;
  bool keepsFloats;
  int chunkLines;
  double compressorBuffers;
};
constexpr MethodInfo kMethods[] = {
    {ExrCompression::None, "none", true, 1, 0},    {ExrCompression::Rle, "rle", true, 1, 2.5},
    {ExrCompression::Zips, "zips", true, 1, 2.1},  {ExrCompression::Zip, "zip", true, 16, 2.1},
    {ExrCompression::Piz, "piz", true, 32, 2.1},   {ExrCompression::Pxr24, "pxr24", false, 16, 2.1},
    {ExrCompression::B44, "b44", true, 32, 2.1}, // compresses half channels only; floats stay
    {ExrCompression::B44a, "b44a", true, 32, 2.1}, {ExrCompression::Dwaa, "dwaa", false, 32, 4},
    {ExrCompression::Dwab, "dwab", false, 256, 4},
};

static_assert(
    [] {
      for (size_t i = 0; i < std::size(kMethods); ++i)
        if (static_cast<size_t>(kMethods[i].method) != i) return false;
      return true;
    }(),
    "kMethods lists the methods in the enum's order");

const MethodInfo& info(ExrCompression c) {
  return kMethods[static_cast<size_t>(c)];
}

} // namespace

const char* exrCompressionName(ExrCompression c) {
  return info(c).name;
}

std::vector<ExrCompression> allExrCompressions() {
  std::vector<ExrCompression> all;
  for (const MethodInfo& m : kMethods) all.push_back(m.method);
  return all;
}

ExrCompression defaultExrCompression(bool halfFloats) {
  return halfFloats ? ExrCompression::Piz : ExrCompression::None;
}

bool keepsFloatsExactly(ExrCompression c) {
  return info(c).keepsFloats;
}

int exrChunkLines(ExrCompression c) {
  return info(c).chunkLines;
}

double exrCompressorBuffers(ExrCompression c) {
  return info(c).compressorBuffers;
}

ExrCompression parseExrCompression(const std::string& text, const std::string& what) {
  std::string names;
  for (ExrCompression c : allExrCompressions()) {
    if (text == exrCompressionName(c)) return c;
    names += names.empty() ? "" : ", ";
    names += exrCompressionName(c);
  }
  throw Error(what + ": expected one of " + names + ", found '" + text + "'");
}

} // namespace nx
