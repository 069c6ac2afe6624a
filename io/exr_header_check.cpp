#include "io/exr_header_check.h"

#include <cstdint>
#include <filesystem>
#include <fstream>

#include "core/error.h"

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

} // namespace

void checkExrHeader(const std::string& path) {
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
  std::string name, type;
  int attributes = 0;
  for (;;) {
    if (!readName(in, 255, name))
      throw Error(path + ": expected header attribute names of at most 255 bytes ending in NUL, "
                         "found the header cut short or a longer name");
    if (name.empty()) { // the end of a header
      if (!multiPart) return;
      if (in.peek() == 0) return; // an empty header ends the list of parts
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
    in.seekg(size, std::ios::cur);
    if (++attributes > kMaxAttributes)
      throw Error(path + ": expected at most " + std::to_string(kMaxAttributes) +
                  " header attributes, found more");
  }
}

} // namespace nx
