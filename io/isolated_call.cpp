#include "io/isolated_call.h"

#include <dlfcn.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include "core/error.h"

namespace nx {
namespace {

using Clock = std::chrono::steady_clock;

// Sends all of `data` (MSG_NOSIGNAL: a dead peer is an error, not SIGPIPE).
bool sendAll(int fd, const char* data, size_t size) {
  while (size > 0) {
    const ssize_t n = ::send(fd, data, size, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n, size -= static_cast<size_t>(n);
  }
  return true;
}

// A message: its length (8 bytes) and its bytes.
bool sendMessage(int fd, const std::string& m) {
  const uint64_t n = m.size();
  return sendAll(fd, reinterpret_cast<const char*>(&n), sizeof n) &&
         sendAll(fd, m.data(), m.size());
}

// Receives `size` bytes before `deadline` (none: wait as long as it takes); false on EOF, an
// error or the deadline.
bool receiveAll(int fd, char* data, size_t size, const Clock::time_point* deadline,
                bool& timedOut) {
  while (size > 0) {
    if (deadline) {
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(*deadline - Clock::now()).count();
      if (left <= 0) {
        timedOut = true;
        return false;
      }
      pollfd p{fd, POLLIN, 0};
      const int ready = ::poll(&p, 1, static_cast<int>(left));
      if (ready < 0 && errno == EINTR) continue;
      if (ready == 0) continue; // the deadline is checked above
    }
    const ssize_t n = ::recv(fd, data, size, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n, size -= static_cast<size_t>(n);
  }
  return true;
}

bool receiveMessage(int fd, std::string& m, const Clock::time_point* deadline, bool& timedOut) {
  uint64_t n = 0;
  if (!receiveAll(fd, reinterpret_cast<char*>(&n), sizeof n, deadline, timedOut)) return false;
  if (n > (uint64_t{1} << 32)) return false;
  m.assign(static_cast<size_t>(n), '\0');
  return receiveAll(fd, m.data(), m.size(), deadline, timedOut);
}

} // namespace

std::string helperProgramPath(const std::string& name) {
  namespace fs = std::filesystem;
  std::vector<fs::path> dirs;
  if (const char* d = std::getenv("NXRENDER_HELPER_DIR"); d && *d) dirs.emplace_back(d);
  Dl_info info{};
  if (::dladdr(reinterpret_cast<void*>(&helperProgramPath), &info) && info.dli_fname) {
    std::error_code ec;
    const fs::path self = fs::canonical(info.dli_fname, ec);
    if (!ec) {
      dirs.push_back(self.parent_path());
      dirs.push_back(self.parent_path().parent_path() / "libexec" / "nxrender");
    }
  }
#ifdef NX_HELPER_BUILD_DIR
  dirs.emplace_back(NX_HELPER_BUILD_DIR);
#endif
#ifdef NX_HELPER_INSTALL_DIR
  dirs.emplace_back(NX_HELPER_INSTALL_DIR);
#endif
  for (const fs::path& d : dirs) {
    const fs::path p = d / name;
    if (::access(p.c_str(), X_OK) == 0) return p.string();
  }
  return "";
}

int serveIsolatedRequests(int fd, const std::function<std::string(const std::string&)>& work) {
  // Each request is answered with 'O' and the reply, 'E' and an nx::Error's message, or 'X' and
  // another exception's.
  for (;;) {
    std::string request;
    bool unused = false;
    if (!receiveMessage(fd, request, nullptr, unused)) return 0; // the parent is gone
    std::string reply;
    try {
      reply = "O" + work(request);
    } catch (const Error& e) {
      reply = std::string("E") + e.what();
    } catch (const std::exception& e) {
      reply = std::string("X") + e.what();
    }
    if (!sendMessage(fd, reply)) return 0;
  }
}

IsolatedWorker::IsolatedWorker(std::string program) : program_(std::move(program)) {}

IsolatedWorker::~IsolatedWorker() {
  const std::lock_guard<std::mutex> lock(mutex_);
  stop();
}

void IsolatedWorker::start() {
  const std::string path = helperProgramPath(program_);
  if (path.empty())
    throw Error("cannot start a reader process: its program " + program_ +
                " is not installed beside nxrender (or set NXRENDER_HELPER_DIR)");
  int fds[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0)
    throw Error(std::string("cannot start a reader process (") + std::strerror(errno) + ")");
  // The helper's end becomes its descriptor 3 (dup2 clears close-on-exec there); every other
  // descriptor of this process is closed by exec where it is close-on-exec.
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[1], 3);
  char* argv[] = {const_cast<char*>(path.c_str()), const_cast<char*>("--serve"), nullptr};
  pid_t pid = -1;
  const int failed = ::posix_spawn(&pid, path.c_str(), &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[1]);
  if (failed != 0) {
    ::close(fds[0]);
    throw Error("cannot start a reader process " + path + " (" + std::strerror(failed) + ")");
  }
  pid_ = pid;
  fd_ = fds[0];
}

void IsolatedWorker::stop() {
  if (pid_ < 0) return;
  ::close(fd_);
  ::kill(pid_, SIGKILL);
  while (::waitpid(pid_, nullptr, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1, fd_ = -1;
}

std::string IsolatedWorker::call(const std::string& request, const std::string& what,
                                 double seconds) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (pid_ < 0) start();
  const Clock::time_point deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                        std::chrono::duration<double>(seconds));
  std::string reply;
  bool timedOut = false;
  if (!sendMessage(fd_, request) || !receiveMessage(fd_, reply, &deadline, timedOut) ||
      reply.empty()) {
    int status = 0;
    if (!timedOut && ::waitpid(pid_, &status, WNOHANG) == pid_) pid_ = -1; // it died
    if (pid_ >= 0)
      stop();
    else {
      ::close(fd_);
      fd_ = -1;
    }
    if (timedOut)
      throw Error(what + ": did not finish within " + numberText(seconds) +
                  " s (the library loops on some malformed input; check the file)");
    throw Error(what + ": the library's reader crashed on this file" +
                (WIFSIGNALED(status) ? " (signal " + std::to_string(WTERMSIG(status)) + ")"
                                     : std::string()) +
                "; a malformed file?");
  }
  if (reply[0] == 'E') throw Error(reply.substr(1));
  if (reply[0] == 'X') throw Error(what + ": " + reply.substr(1));
  return reply.substr(1);
}

} // namespace nx
