#include "io/exr_compression.h"

#include <cstddef>
#include <iterator>

#include "core/error.h"

namespace nx {

namespace {

// Each method's name and whether it stores float channels bit for bit, in the enum's order.
struct MethodInfo {
  ExrCompression method;
  const char* name;
  bool keepsFloats;
};
constexpr MethodInfo kMethods[] = {
    {ExrCompression::None, "none", true},  {ExrCompression::Rle, "rle", true},
    {ExrCompression::Zips, "zips", true},  {ExrCompression::Zip, "zip", true},
    {ExrCompression::Piz, "piz", true},    {ExrCompression::Pxr24, "pxr24", false},
    {ExrCompression::B44, "b44", true}, // compresses half channels only; floats stay as they are
    {ExrCompression::B44a, "b44a", true},  {ExrCompression::Dwaa, "dwaa", false},
    {ExrCompression::Dwab, "dwab", false},
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
