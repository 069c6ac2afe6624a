#include "io/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/error.h"
#include "core/hash.h"

namespace nx {
namespace fs = std::filesystem;
namespace {

// The file a write lands in: `path`, or what it points to when it is a symlink (renaming onto
// the link would replace the link with a file).
fs::path finalTarget(const std::string& path) {
  std::error_code ec;
  if (fs::is_symlink(path, ec)) return fs::weakly_canonical(fs::path(path), ec);
  return fs::path(path);
}

fs::path directoryOf(const fs::path& target) {
  return target.has_parent_path() ? target.parent_path() : fs::path(".");
}

// ".nxtmp-<hash of the target's name>": short whatever the target's name (a 250-byte name plus
// a suffix passed the 255-byte limit), and recognisable as ours for the clean-up.
std::string tempPrefix(const fs::path& target) {
  char buf[32];
  std::snprintf(buf, sizeof buf, ".nxtmp-%016llx-",
                static_cast<unsigned long long>(fnv1a64(target.filename().string())));
  return buf;
}

fs::path tempNameFor(const fs::path& target, long pid = ::getpid()) {
  return directoryOf(target) / (tempPrefix(target) + std::to_string(pid));
}

// Removes "<prefix><pid>" files of this target whose process no longer runs.
void removeStaleTemporaries(const fs::path& target) {
  const std::string prefix = tempPrefix(target);
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(directoryOf(target), ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string pidText = name.substr(prefix.size());
    char* end = nullptr;
    const long pid = std::strtol(pidText.c_str(), &end, 10);
    if (pidText.empty() || *end != '\0' || pid <= 0) continue;
    if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) fs::remove(entry.path(), ec);
  }
}

} // namespace

void writeAtomically(const std::string& path,
                     const std::function<void(const std::string&)>& write) {
  const fs::path target = finalTarget(path);
  const std::string temp = tempNameFor(target).string();
  try {
    write(temp);
  } catch (const std::exception& e) {
    std::remove(temp.c_str());
    throw Error(path + ": cannot write the file: " + e.what());
  }
  if (std::rename(temp.c_str(), target.c_str()) != 0) {
    const std::string cause = std::strerror(errno);
    throw Error(path + ": cannot move the finished file into place (" + cause +
                "); it is kept as " + temp);
  }
}

void checkWritable(const std::string& path) {
  const fs::path target = finalTarget(path);
  const fs::path dir = directoryOf(target);
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw Error(path + ": the output directory '" + dir.string() + "' does not exist");
  if (fs::is_directory(target, ec)) throw Error(path + ": is a directory, not a file name");
  if (target.filename().string().size() > 255)
    throw Error(path + ": expected a file name of at most 255 bytes");
  const std::string probe = tempNameFor(target).string() + "p";
  std::FILE* f = std::fopen(probe.c_str(), "wb");
  if (!f)
    throw Error(path + ": cannot create files in '" + dir.string() + "': " + std::strerror(errno));
  std::fclose(f);
  std::remove(probe.c_str());
  // An existing target must be replaceable: rename fails on an immutable file (EPERM), and a
  // read-only one is somebody's wish not to overwrite it.
  if (fs::exists(target, ec) && ::access(target.c_str(), W_OK) != 0)
    throw Error(path + ": exists and cannot be replaced (" + std::strerror(errno) + ")");
  removeStaleTemporaries(target);
}

std::string atomicTempName(const std::string& path, long pid) {
  return tempNameFor(finalTarget(path), pid).string();
}

void checkFreeSpace(const std::string& path, double bytes) {
  const fs::path dir = directoryOf(finalTarget(path));
  struct statvfs st {};
  if (statvfs(dir.c_str(), &st) != 0) return; // unknown: the write itself will report
  const double available = static_cast<double>(st.f_bavail) * static_cast<double>(st.f_frsize);
  if (available < bytes)
    throw Error(path + ": needs about " + std::to_string(static_cast<long long>(bytes / 1e6)) +
                " MB but only " + std::to_string(static_cast<long long>(available / 1e6)) +
                " MB are free in '" + dir.string() + "'");
}

OutputLock::OutputLock(const std::string& path) {
  fd_ = ::open(directoryOf(finalTarget(path)).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd_ >= 0 && ::flock(fd_, LOCK_EX) != 0) {
    ::close(fd_);
    fd_ = -1; // no lock to be had (a file system without flock): write unlocked
  }
}

OutputLock::~OutputLock() {
  if (fd_ >= 0) ::close(fd_); // closing releases the lock
}

} // namespace nx
