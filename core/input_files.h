#pragma once
// The files a program has read as inputs, so that no output replaces one (nxrelight in.exr
// -o in.exr replaced a relightable file with its relit image). Files are compared by identity
// (device and inode): a symlink, a hard link, "./in.exr" and "in.exr" are one file.

#include <optional>
#include <string>

namespace nx {

/// Starts recording the files this process reads (a program's main does so; a library in a
/// long-lived process such as Python does not: its images carry their own sources).
void recordInputFiles();

/// Notes `path` as an input when recording (requireRegularFile does so for every file a
/// reader takes; programs also note their command-line inputs before checking outputs).
void noteInputFile(const std::string& path);

/// Lets outputs replace the input at `path` (a render resumed into the file it continues,
/// which then holds all the input held and more).
void allowReplacingInput(const std::string& path);

/// The input the file at `path` is (as it was named when noted), unless its replacement was
/// allowed; none for a file that is no input or does not exist.
std::optional<std::string> inputFileAt(const std::string& path);

/// True when both paths name one existing file (device and inode).
bool sameFile(const std::string& a, const std::string& b);

} // namespace nx
