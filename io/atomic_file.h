#pragma once
// Writing output files so that a reader never sees a half-written one.

#include <functional>
#include <string>

namespace nx {

/// Calls write(tempPath) for a temporary name in the target's directory, then renames the
/// temporary file onto `path`. On any failure the temporary file is removed and an nx::Error
/// names the path and the cause.
void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write);

/// Throws nx::Error unless a file can be created in the directory of `path` (checked by
/// creating and removing a probe file), so renders fail before any work.
void checkWritable(const std::string& path);

/// Throws nx::Error if the file system holding `path` has less than `bytes` available.
void checkFreeSpace(const std::string& path, double bytes);

} // namespace nx
