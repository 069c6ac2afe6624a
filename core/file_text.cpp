#include "core/file_text.h"

#include <cctype>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/input_files.h"

namespace nx {
namespace {
std::string limitText(std::uintmax_t bytes) {
  return bytes >= (1ull << 40) ? std::to_string(bytes >> 40) + " TiB"
                               : std::to_string(bytes >> 20) + " MiB";
}
// "a scene file", "an EXR file", "an ENVI header".
std::string withArticle(const std::string& what) {
  const char c = what.empty() ? 'x' : static_cast<char>(std::tolower(what[0]));
  return (c == 'a' || c == 'e' || c == 'i' || c == 'o' ? "an " : "a ") + what;
}
} // namespace

void requireRegularFile(const std::string& path, std::uintmax_t maxBytes, const std::string& what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (st.type() == fs::file_type::not_found || st.type() == fs::file_type::none)
    throw Error(path + ": cannot open the " + what);
  if (st.type() == fs::file_type::directory)
    throw Error(path + ": expected " + withArticle(what) + ", found a directory");
  if (st.type() != fs::file_type::regular)
    throw Error(path + ": expected " + withArticle(what) +
                " (a regular file), found a FIFO, socket or device");
  if (fs::file_size(path, ec) > maxBytes)
    throw Error(path + ": expected " + withArticle(what) + " of at most " + limitText(maxBytes));
  noteInputFile(path); // no output of this program may replace it
}

std::string readRegularFile(const std::string& path, std::uintmax_t maxBytes,
                            const std::string& what) {
  requireRegularFile(path, maxBytes, what);
  const std::string limit = limitText(maxBytes);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the " + what);
  std::string text;
  char buf[1 << 16];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) {
    text.append(buf, static_cast<size_t>(in.gcount()));
    if (text.size() > maxBytes)
      throw Error(path + ": expected " + withArticle(what) + " of at most " + limit);
  }
  if (in.bad()) throw Error(path + ": cannot read the " + what);
  return text;
}

} // namespace nx
