#pragma once
// Writing output files so that a reader never sees a half-written one, and a finished render
// is never lost to a failed rename.

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace nx {

/// Throws nx::Error if the file at `path` (through links, hard links or another spelling) is
/// one of the program's inputs (core/input_files.h) that it may not replace.
void refuseReplacingAnInput(const std::string& path);

/// Calls write(tempPath) for a short temporary name in the target's directory
/// (".nxtmp-<pid>-<hash of the name>"), then renames it onto `path` (onto the file a symlink
/// points to, if `path` is one). Refused first if `path` is an input (refuseReplacingAnInput). If
/// writing fails, the temporary file is removed and an nx::Error names the path and the cause; if
/// only the final rename fails, the finished file is kept and the error says where it is.
void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write);

/// Throws nx::Error unless `path` can be written before any work starts: its directory exists
/// and accepts new files (a probe file is created and removed), and an existing target (or
/// the file its symlink points to) can be replaced (not immutable or read-only) and is none of
/// the program's inputs (refuseReplacingAnInput; writeAtomically checks again). Also removes
/// temporary files for this target left by processes that no longer run (SIGKILL during a
/// write), after completing any AtomicFileGroup such a process left half committed in that
/// directory.
void checkWritable(const std::string& path);

/// Several outputs replaced as one (an EXR and its preview). While a group is open on a thread,
/// writeAtomically on that thread writes each file under its temporary name and leaves it
/// there; commit() then puts a journal naming the files in place, renames every temporary onto
/// its target and removes the journal. A process killed during the renames leaves the journal,
/// and the next checkWritable of a target in that directory completes the renames: the outputs
/// are the old set or the new one, never a mix (a SIGKILL between the EXR's and the preview's
/// rename left the new EXR beside the old preview). A group destroyed without commit() removes
/// its temporaries and leaves the targets as they were.
class AtomicFileGroup {
public:
  /// Opens the group on this thread (one at a time).
  AtomicFileGroup();
  ~AtomicFileGroup();
  AtomicFileGroup(const AtomicFileGroup&) = delete;
  AtomicFileGroup& operator=(const AtomicFileGroup&) = delete;
  /// Replaces the targets of the files written since the group opened, as one.
  void commit();
  /// The group open on this thread, or null (for writeAtomically).
  static AtomicFileGroup* current();
  /// A finished temporary file and the target it replaces (called by writeAtomically).
  void defer(const std::string& temp, const std::string& target);

private:
  std::vector<std::pair<std::string, std::string>> files_; // (temporary, target)
  bool committed_ = false;
};

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
