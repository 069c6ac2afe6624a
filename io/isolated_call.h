#pragma once
// Running a library call that may crash or never return on some inputs in a child process
// with a time limit. OpenCV 4.6's FileStorage reader (Debian 12's) loops forever on some
// malformed YAML (a line "e---" in a fuzzed file) and read past NUL-bearing text; no check
// before it can rule out every such input, so it reads in a process that can be killed.

#include <functional>
#include <string>

namespace nx {

/// Runs `work` in a forked child and returns the bytes it returned. An nx::Error it throws is
/// rethrown here with its message; a child that crashes, is killed, or runs past `seconds` is
/// an nx::Error "<what>: ..." saying which. The child shares nothing with the caller after the
/// fork: `work` must only read its inputs and return its result (no output, no shared state).
std::string runIsolated(const std::function<std::string()>& work, double seconds,
                        const std::string& what);

} // namespace nx
