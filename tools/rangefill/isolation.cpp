#include "isolation.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <system_error>

namespace rangefill::cli {

namespace {

using Clock = std::chrono::steady_clock;

struct Running {
  int index = 0;
  pid_t pid = 0;
  int fd = -1;  // read end of the child's pipe
  Clock::time_point start;
  std::string output;
};

[[noreturn]] void fail(const char* what) {
  throw std::system_error(errno, std::generic_category(), what);
}

// In the child: runs the job, writes its output to `fd` and exits without running anything of the
// parent's (no atexit handlers, no stdio flush).
[[noreturn]] void run_child(int index, int fd, pid_t parent,
                            const std::function<std::string(int)>& job) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(1);  // the parent died before prctl
  std::string output;
  try {
    output = job(index);
  } catch (...) {
    ::_exit(1);
  }
  for (size_t written = 0; written < output.size();) {
    const ssize_t n = ::write(fd, output.data() + written, output.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) ::_exit(1);
    written += static_cast<size_t>(n);
  }
  ::_exit(0);
}

Running start(int index, const std::function<std::string(int)>& job) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) fail("pipe");
  std::fflush(nullptr);  // nothing buffered is written twice
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) fail("fork");
  if (pid == 0) {
    ::close(fds[0]);
    run_child(index, fds[1], parent, job);
  }
  ::close(fds[1]);
  return {index, pid, fds[0], Clock::now(), {}};
}

std::string describe(int status) {
  if (WIFEXITED(status)) return "exited with " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    return "crashed (signal " + std::to_string(signal) + ": " + ::strsignal(signal) + ")";
  }
  return "ended abnormally";
}

// Waits for the child and turns what it left into a result.
ChildResult finish(Running& job, bool timed_out, double timeout) {
  ::close(job.fd);
  if (timed_out) ::kill(job.pid, SIGKILL);
  int status = 0;
  while (::waitpid(job.pid, &status, 0) < 0 && errno == EINTR) {
  }
  ChildResult result;
  result.seconds = std::chrono::duration<double>(Clock::now() - job.start).count();
  if (timed_out) {
    char text[64];
    std::snprintf(text, sizeof text, "timed out after %g s", timeout);
    result.failure = text;
  } else if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    result.completed = true;
    result.output = std::move(job.output);
  } else {
    result.failure = describe(status);
  }
  return result;
}

}  // namespace

std::vector<ChildResult> run_in_children(int count, int parallel, double timeout,
                                         const std::function<std::string(int)>& job,
                                         const std::function<void(int, const ChildResult&)>& done) {
  std::vector<ChildResult> results(count);
  std::vector<Running> running;
  int next = 0;
  while (next < count || !running.empty()) {
    while (next < count && static_cast<int>(running.size()) < std::max(1, parallel)) {
      running.push_back(start(next++, job));
    }
    // Wait for output, an end of file, or the first deadline.
    int wait_ms = -1;
    if (timeout > 0) {
      for (const Running& r : running) {
        const double left = timeout - std::chrono::duration<double>(Clock::now() - r.start).count();
        const int ms = std::max(0, static_cast<int>(std::ceil(left * 1000)));
        wait_ms = wait_ms < 0 ? ms : std::min(wait_ms, ms);
      }
    }
    std::vector<pollfd> fds;
    for (const Running& r : running) fds.push_back({r.fd, POLLIN, 0});
    if (::poll(fds.data(), fds.size(), wait_ms) < 0 && errno != EINTR) fail("poll");
    for (size_t k = running.size(); k-- > 0;) {
      Running& r = running[k];
      bool ended = false, timed_out = false;
      if (fds[k].revents & (POLLIN | POLLHUP | POLLERR)) {
        char buffer[65536];
        const ssize_t n = ::read(r.fd, buffer, sizeof buffer);
        if (n > 0) r.output.append(buffer, static_cast<size_t>(n));
        ended = n == 0 || (n < 0 && errno != EINTR && errno != EAGAIN);
      }
      if (!ended && timeout > 0 &&
          std::chrono::duration<double>(Clock::now() - r.start).count() >= timeout) {
        ended = timed_out = true;
      }
      if (!ended) continue;
      const int index = r.index;
      results[index] = finish(r, timed_out, timeout);
      running.erase(running.begin() + static_cast<std::ptrdiff_t>(k));
      done(index, results[index]);
    }
  }
  return results;
}

}  // namespace rangefill::cli
