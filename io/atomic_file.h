#pragma once
// Writing output files so that a reader never sees a half-written one, and a finished render
// is never lost to a failed rename.

#include <functional>
#include <string>

namespace nx {

/// Calls write(tempPath) for a short temporary name in the target's directory
/// (".nxtmp-<pid>-<hash of the name>"), then renames it onto `path` (onto the file a symlink
/// points to, if `path` is one). If writing fails, the temporary file is removed and an
/// nx::Error names the path and the cause; if only the final rename fails, the finished file
/// is kept and the error says where it is.
void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write);

/// Throws nx::Error unless `path` can be written before any work starts: its directory exists
/// and accepts new files (a probe file is created and removed), and an existing target (or
/// the file its symlink points to) can be replaced (not immutable or read-only). Also removes
/// temporary files for this target left by processes that no longer run (SIGKILL during a
/// write).
void checkWritable(const std::string& path);

/// The temporary name writeAtomically uses for `path` in process `pid` (for tests and tools).
std::string atomicTempName(const std::string& path, long pid);

/// Throws nx::Error if the file system holding `path` has less than `bytes` available.
void checkFreeSpace(const std::string& path, double bytes);

/// An exclusive lock on the directory of an output, held while a program writes its files
/// there (the EXR and its preview), so that two processes writing the same output leave one
/// run's pair, never one's EXR beside the other's PNG. Released when destroyed.
class OutputLock {
public:
  /// Waits for and takes the lock of the directory holding `path`.
  explicit OutputLock(const std::string& path);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

private:
  int fd_ = -1;
};

} // namespace nx
