#include "io/exr_compression.h"

#include "core/error.h"

namespace nx {

const char* exrCompressionName(ExrCompression c) {
  switch (c) {
  case ExrCompression::None:
    return "none";
  case ExrCompression::Rle:
    return "rle";
  case ExrCompression::Zips:
    return "zips";
  case ExrCompression::Zip:
    return "zip";
  case ExrCompression::Piz:
    return "piz";
  case ExrCompression::Pxr24:
    return "pxr24";
  case ExrCompression::B44:
    return "b44";
  case ExrCompression::B44a:
    return "b44a";
  case ExrCompression::Dwaa:
    return "dwaa";
  case ExrCompression::Dwab:
    return "dwab";
  }
  return "?";
}

std::vector<ExrCompression> allExrCompressions() {
  return {ExrCompression::None, ExrCompression::Rle,   ExrCompression::Zips, ExrCompression::Zip,
          ExrCompression::Piz,  ExrCompression::Pxr24, ExrCompression::B44,  ExrCompression::B44a,
          ExrCompression::Dwaa, ExrCompression::Dwab};
}

ExrCompression defaultExrCompression(bool halfFloats) {
  return halfFloats ? ExrCompression::Piz : ExrCompression::None;
}

bool keepsFloatsExactly(ExrCompression c) {
  switch (c) {
  case ExrCompression::None:
  case ExrCompression::Rle:
  case ExrCompression::Zips:
  case ExrCompression::Zip:
  case ExrCompression::Piz:
  case ExrCompression::B44: // compresses half channels only; floats are stored as they are
  case ExrCompression::B44a:
    return true;
  default:
    return false;
  }
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
