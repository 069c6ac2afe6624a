#pragma once
// Running a library call that may crash or never return on some inputs in another process
// with a time limit. OpenCV 4.6's FileStorage reader (Debian 12's) loops forever on some
// malformed YAML (a line "e---" in a fuzzed file) and read past NUL-bearing text; no check
// before it can rule out every such input, so it reads in a process that can be killed.
//
// The process is a helper program started with posix_spawn (fork and exec in one step), never
// a fork of the caller: the caller may be multi-threaded (TBB's workers, Python, nxdataset
// --jobs), and a forked child of such a process can deadlock on a lock another thread held at
// the fork.

#include <sys/types.h>

#include <functional>
#include <mutex>
#include <string>

namespace nx {

/// A helper process that answers requests: started at the first call, kept for the next ones
/// (a start per call cost 24 ms under the sanitizers), and replaced after a request crashed it
/// or ran past the time limit. Thread-safe; the helper exits when this object is destroyed or
/// its parent dies.
class IsolatedWorker {
public:
  /// `program`: the helper's file name (found by helperProgramPath), which serves requests
  /// with serveIsolatedRequests.
  explicit IsolatedWorker(std::string program);
  ~IsolatedWorker();
  IsolatedWorker(const IsolatedWorker&) = delete;
  IsolatedWorker& operator=(const IsolatedWorker&) = delete;

  /// The reply to `request` within `seconds`. Throws nx::Error: the work's own, or "<what>:
  /// did not finish within N s ..." / "<what>: the library's reader crashed ..." when the
  /// helper did not answer (`what` names the reader: "calib.yml: OpenCV's calibration
  /// reader"), or "cannot start ..." when the helper cannot be found or started.
  std::string call(const std::string& request, const std::string& what, double seconds);

private:
  void start();
  void stop();
  std::string program_;
  std::mutex mutex_;
  pid_t pid_ = -1;
  int fd_ = -1; ///< the parent's end of the socket pair
};

/// The helper program's loop: reads requests from socket `fd` and answers each with `work`'s
/// reply (an nx::Error it throws is passed on to the caller) until the parent closes the socket.
/// Returns the exit status.
int serveIsolatedRequests(int fd, const std::function<std::string(const std::string&)>& work);

/// Where the helper program `name` is: in $NXRENDER_HELPER_DIR if set, else beside the program
/// or Python module this code is linked into, in its ../libexec/nxrender, the build tree's
/// apps/ or the install prefix's libexec/nxrender; "" if in none of them.
std::string helperProgramPath(const std::string& name);

} // namespace nx
