#pragma once
// Running a library call that may crash or never return on some inputs in a child process
// with a time limit. OpenCV 4.6's FileStorage reader (Debian 12's) loops forever on some
// malformed YAML (a line "e---" in a fuzzed file) and read past NUL-bearing text; no check
// before it can rule out every such input, so it reads in a process that can be killed.

#include <sys/types.h>

#include <functional>
#include <mutex>
#include <string>

namespace nx {

/// A child process that answers requests with one function: forked at the first call, kept
/// for the next ones (a fork per call cost 24 ms under the sanitizers), and replaced after a
/// request crashed it or ran past the time limit. Thread-safe; the child exits when this
/// object is destroyed or its parent dies.
class IsolatedWorker {
public:
  /// `work` maps a request to its reply and may throw nx::Error (its message is rethrown by
  /// call).
  explicit IsolatedWorker(std::function<std::string(const std::string&)> work);
  ~IsolatedWorker();
  IsolatedWorker(const IsolatedWorker&) = delete;
  IsolatedWorker& operator=(const IsolatedWorker&) = delete;

  /// The reply to `request` within `seconds`. Throws nx::Error: the work's own, or "<what>:
  /// did not finish within N s ..." / "<what>: the library's reader crashed ..." when the child
  /// did not answer (`what` names the reader: "calib.yml: OpenCV's calibration reader").
  std::string call(const std::string& request, const std::string& what, double seconds);

  /// Called first in every child process (null: nothing). The fuzzer sets it so that a
  /// library crash the child contains is not also written as a finding of the fuzzed process
  /// (the child inherits the fuzzer's crash handler with its memory).
  static inline void (*childStarted)() = nullptr;

private:
  void start();
  void stop();
  std::function<std::string(const std::string&)> work_;
  std::mutex mutex_;
  pid_t pid_ = -1;
  int fd_ = -1; ///< the parent's end of the socket pair
};

} // namespace nx
