#include "io/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/error.h"
#include "core/hash.h"
#include "core/input_files.h"

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

bool processGone(long pid) {
  return ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

// The pid in ".nxtmp-<16 hex digits>-<pid><suffix>" (a temporary of ours) and the suffix; 0
// when the name is not one of ours.
long pidOf(const std::string& name, std::string& suffix) {
  const std::string head = ".nxtmp-";
  if (name.size() < head.size() + 18 || name.rfind(head, 0) != 0 || name[head.size() + 16] != '-')
    return 0;
  for (size_t i = head.size(); i < head.size() + 16; ++i)
    if (!std::isxdigit(static_cast<unsigned char>(name[i]))) return 0;
  const char* start = name.c_str() + head.size() + 17;
  char* end = nullptr;
  const long pid = std::strtol(start, &end, 10);
  if (end == start || pid <= 0 || *start == '-' || *start == '+') return 0;
  suffix = end;
  return pid;
}

constexpr const char* kJournalSuffix = ".group";

// Completes the groups that processes which no longer run left half committed in `dir`: every
// temporary a journal names that is still there is renamed onto its target.
void completeInterruptedGroups(const fs::path& dir) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    std::string suffix;
    const long pid = pidOf(name, suffix);
    if (pid == 0 || suffix.size() < std::strlen(kJournalSuffix) ||
        suffix.compare(suffix.size() - std::strlen(kJournalSuffix), std::string::npos,
                       kJournalSuffix) != 0 ||
        !processGone(pid))
      continue;
    std::FILE* f = std::fopen(entry.path().c_str(), "rb");
    if (!f) continue;
    std::string text;
    char buf[4096];
    for (size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) text.append(buf, n);
    std::fclose(f);
    size_t pos = 0;
    while (pos < text.size()) {
      const size_t end = text.find('\n', pos), tab = text.find('\t', pos);
      if (end == std::string::npos || tab == std::string::npos || tab > end) break;
      const std::string temp = text.substr(pos, tab - pos),
                        target = text.substr(tab + 1, end - tab - 1);
      if (fs::exists(temp, ec)) std::rename(temp.c_str(), target.c_str());
      pos = end + 1;
    }
    fs::remove(entry.path(), ec);
  }
}

// Removes "<prefix><pid>..." files of this target whose process no longer runs.
void removeStaleTemporaries(const fs::path& target) {
  completeInterruptedGroups(directoryOf(target));
  const std::string prefix = tempPrefix(target);
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(directoryOf(target), ec)) {
    const std::string name = entry.path().filename().string();
    std::string suffix;
    const long pid = name.rfind(prefix, 0) == 0 ? pidOf(name, suffix) : 0;
    if (pid != 0 && processGone(pid)) fs::remove(entry.path(), ec);
  }
}

thread_local AtomicFileGroup* gOpenGroup = nullptr;

} // namespace

void refuseReplacingAnInput(const std::string& path) {
  if (const std::optional<std::string> input = inputFileAt(path))
    throw Error(path + ": expected an output that is none of the inputs, found the input " +
                (*input == path ? std::string("itself") : *input) +
                " (writing would destroy it: choose another output name)");
}

void writeAtomically(const std::string& path,
                     const std::function<void(const std::string&)>& write) {
  refuseReplacingAnInput(path); // an input read after the outputs were checked
  const fs::path target = finalTarget(path);
  const std::string temp = tempNameFor(target).string();
  try {
    write(temp);
  } catch (const std::exception& e) {
    std::remove(temp.c_str());
    throw Error(path + ": cannot write the file: " + e.what());
  }
  if (AtomicFileGroup* group = AtomicFileGroup::current()) {
    group->defer(temp, target.string()); // renamed with the rest of the group
    return;
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
  refuseReplacingAnInput(path);
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

AtomicFileGroup::AtomicFileGroup() {
  if (gOpenGroup) throw Error("internal error: a group of output files is open already");
  gOpenGroup = this;
}

AtomicFileGroup::~AtomicFileGroup() {
  gOpenGroup = nullptr;
  if (!committed_)
    for (const auto& [temp, target] : files_) std::remove(temp.c_str());
}

AtomicFileGroup* AtomicFileGroup::current() {
  return gOpenGroup;
}

void AtomicFileGroup::defer(const std::string& temp, const std::string& target) {
  files_.emplace_back(temp, target);
}

void AtomicFileGroup::commit() {
  gOpenGroup = nullptr;
  committed_ = true;
  if (files_.empty()) return;
  // The journal, itself put in place by a rename: from then on the group is complete on disk.
  const fs::path first(files_.front().second);
  const std::string journal = tempNameFor(first).string() + kJournalSuffix,
                    journalTemp = journal + ".tmp";
  std::string text;
  // Absolute names: the run that may complete the group can work in another directory.
  std::error_code ec;
  for (const auto& [temp, target] : files_)
    text += fs::absolute(temp, ec).string() + "\t" + fs::absolute(target, ec).string() + "\n";
  std::FILE* f = std::fopen(journalTemp.c_str(), "wb");
  const bool written = f && std::fwrite(text.data(), 1, text.size(), f) == text.size();
  if (f && std::fclose(f) != 0) f = nullptr;
  if (!written || !f || std::rename(journalTemp.c_str(), journal.c_str()) != 0) {
    const std::string cause = std::strerror(errno);
    std::remove(journalTemp.c_str());
    for (const auto& [temp, target] : files_) std::remove(temp.c_str());
    throw Error(first.string() + ": cannot write the outputs' journal (" + cause +
                "); nothing was replaced");
  }
  std::string failed;
  for (const auto& [temp, target] : files_)
    if (std::rename(temp.c_str(), target.c_str()) != 0)
      failed += (failed.empty() ? "" : "; ") + target + " (" + std::strerror(errno) +
                "; it is kept as " + temp + ")";
  std::remove(journal.c_str());
  if (!failed.empty()) throw Error("cannot move the finished files into place: " + failed);
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
