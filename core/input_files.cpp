#include "core/input_files.h"

#include <sys/stat.h>

#include <map>
#include <mutex>
#include <set>
#include <utility>

namespace nx {
namespace {

using FileId = std::pair<dev_t, ino_t>;

std::optional<FileId> idOf(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return std::nullopt; // follows links
  return FileId{st.st_dev, st.st_ino};
}

// The record of one process: its inputs by identity, and those it may replace.
struct InputRecord {
  std::mutex mutex;
  bool recording = false;
  std::map<FileId, std::string> inputs;
  std::set<FileId> replaceable;
};

InputRecord& record() {
  static InputRecord r;
  return r;
}

} // namespace

void recordInputFiles() {
  const std::lock_guard<std::mutex> lock(record().mutex);
  record().recording = true;
}

void noteInputFile(const std::string& path) {
  InputRecord& r = record();
  const std::lock_guard<std::mutex> lock(r.mutex);
  if (!r.recording) return;
  if (const auto id = idOf(path)) r.inputs.emplace(*id, path);
}

void allowReplacingInput(const std::string& path) {
  InputRecord& r = record();
  const std::lock_guard<std::mutex> lock(r.mutex);
  if (const auto id = idOf(path)) r.replaceable.insert(*id);
}

std::optional<std::string> inputFileAt(const std::string& path) {
  const auto id = idOf(path);
  if (!id) return std::nullopt;
  InputRecord& r = record();
  const std::lock_guard<std::mutex> lock(r.mutex);
  const auto it = r.inputs.find(*id);
  if (it == r.inputs.end() || r.replaceable.count(*id)) return std::nullopt;
  return it->second;
}

bool sameFile(const std::string& a, const std::string& b) {
  const auto ia = idOf(a), ib = idOf(b);
  return ia && ib && *ia == *ib;
}

} // namespace nx
