#include "io/atomic_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sys/statvfs.h>
#include <unistd.h>

#include "core/error.h"

namespace nx {
namespace {
std::string tempNameFor(const std::string& path) {
  return path + ".tmp-" + std::to_string(::getpid());
}
} // namespace

void writeAtomically(const std::string& path,
                     const std::function<void(const std::string&)>& write) {
  const std::string temp = tempNameFor(path);
  try {
    write(temp);
  } catch (const std::exception& e) {
    std::remove(temp.c_str());
    throw Error(path + ": cannot write the file: " + e.what());
  }
  if (std::rename(temp.c_str(), path.c_str()) != 0) {
    const std::string cause = std::strerror(errno);
    std::remove(temp.c_str());
    throw Error(path + ": cannot move the finished file into place: " + cause);
  }
}

void checkWritable(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw Error(path + ": the output directory '" + dir.string() + "' does not exist");
  if (fs::is_directory(target, ec)) throw Error(path + ": is a directory, not a file name");
  const std::string probe = tempNameFor(path) + ".probe";
  std::FILE* f = std::fopen(probe.c_str(), "wb");
  if (!f)
    throw Error(path + ": cannot create files in '" + dir.string() + "': " + std::strerror(errno));
  std::fclose(f);
  std::remove(probe.c_str());
}

void checkFreeSpace(const std::string& path, double bytes) {
  const std::filesystem::path target(path);
  const std::string dir = target.has_parent_path() ? target.parent_path().string() : ".";
  struct statvfs fs {};
  if (statvfs(dir.c_str(), &fs) != 0) return; // unknown: the write itself will report
  const double available = static_cast<double>(fs.f_bavail) * static_cast<double>(fs.f_frsize);
  if (available < bytes)
    throw Error(path + ": needs about " + std::to_string(static_cast<long long>(bytes / 1e6)) +
                " MB but only " + std::to_string(static_cast<long long>(available / 1e6)) +
                " MB are free in '" + dir + "'");
}

} // namespace nx
