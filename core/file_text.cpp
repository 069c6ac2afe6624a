#include "core/file_text.h"

#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace nx {

std::string readRegularFile(const std::string& path, std::uintmax_t maxBytes,
                            const std::string& what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (st.type() == fs::file_type::not_found || st.type() == fs::file_type::none)
    throw Error(path + ": cannot open the " + what);
  if (st.type() == fs::file_type::directory)
    throw Error(path + ": expected a " + what + ", found a directory");
  if (st.type() != fs::file_type::regular)
    throw Error(path + ": expected a " + what +
                " (a regular file), found a FIFO, socket or device");
  const std::string limit = std::to_string(maxBytes >> 20) + " MiB";
  if (fs::file_size(path, ec) > maxBytes)
    throw Error(path + ": expected a " + what + " of at most " + limit);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the " + what);
  std::string text;
  char buf[1 << 16];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) {
    text.append(buf, static_cast<size_t>(in.gcount()));
    if (text.size() > maxBytes) throw Error(path + ": expected a " + what + " of at most " + limit);
  }
  if (in.bad()) throw Error(path + ": cannot read the " + what);
  return text;
}

} // namespace nx
