#include "io/isolated_call.h"

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

#include "core/error.h"

namespace nx {
namespace {

// Writes all of `data` (the child's reply) to `fd`.
void writeAll(int fd, const std::string& data) {
  size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    done += static_cast<size_t>(n);
  }
}

} // namespace

std::string runIsolated(const std::function<std::string()>& work, double seconds,
                        const std::string& what) {
  int fds[2];
  if (::pipe(fds) != 0)
    throw Error(what + ": cannot start a reader process (" + std::strerror(errno) + ")");
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]), ::close(fds[1]);
    throw Error(what + ": cannot start a reader process (" + std::strerror(errno) + ")");
  }
  if (pid == 0) { // the child: its reply is 'O' and the result, or 'E' and the message
    ::close(fds[0]);
    std::string reply;
    try {
      reply = "O" + work();
    } catch (const Error& e) {
      reply = std::string("E") + e.what();
    } catch (const std::exception& e) {
      reply = std::string("E") + what + ": " + e.what();
    }
    writeAll(fds[1], reply);
    ::_exit(0); // no destructors or exit handlers of the parent's state
  }
  ::close(fds[1]);
  std::string reply;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  bool timedOut = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timedOut = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(left.count()));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue; // the deadline is checked above
    char buf[1 << 14];
    const ssize_t n = ::read(fds[0], buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break; // the child closed its end: done (or dead)
    reply.append(buf, static_cast<size_t>(n));
  }
  ::close(fds[0]);
  if (timedOut) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (timedOut)
    throw Error(what + ": did not finish within " + std::to_string(static_cast<int>(seconds)) +
                " s (the library loops on some malformed input; check the file)");
  if (WIFSIGNALED(status) || reply.empty())
    throw Error(what + ": the library's reader crashed on this file (signal " +
                std::to_string(WIFSIGNALED(status) ? WTERMSIG(status) : 0) +
                "; a malformed file?)");
  if (reply[0] == 'E') throw Error(reply.substr(1));
  return reply.substr(1);
}

} // namespace nx
