#pragma once
// Runs a piece of a test in a forked child whose address space is capped
// (RLIMIT_AS) at what it already uses plus a little headroom. A reader that
// allocates what a hostile header asks for before checking it then fails in
// the child (std::bad_alloc, or a sanitizer's out-of-memory report) instead
// of taking gigabytes from the machine, and the test sees the difference.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <exception>
#include <fstream>
#include <functional>
#include <string>

namespace bounce::test {

// Bytes of address space this process has mapped now.
inline std::size_t mapped_bytes() {
  std::ifstream statm("/proc/self/statm");
  std::size_t pages = 0;
  statm >> pages;
  return pages * static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
}

// What `body` returned in the capped child; "exception: WHAT" when it threw,
// or how the child ended when it did not get to answer.
inline std::string with_memory_cap(const std::function<std::string()>& body,
                                   std::size_t headroom_bytes = std::size_t(256) << 20) {
  int pipe_fds[2];
  if (::pipe(pipe_fds) != 0) return "pipe failed";
  const pid_t pid = ::fork();
  if (pid < 0) return "fork failed";
  if (pid == 0) {
    ::close(pipe_fds[0]);
    const rlim_t cap = mapped_bytes() + headroom_bytes;
    const rlimit limit{cap, cap};
    std::string answer;
    if (::setrlimit(RLIMIT_AS, &limit) != 0) {
      answer = "setrlimit failed";
    } else {
      try {
        answer = body();
      } catch (const std::exception& e) {
        answer = std::string("exception: ") + e.what();
      }
    }
    for (std::size_t at = 0; at < answer.size();) {
      const ssize_t n = ::write(pipe_fds[1], answer.data() + at, answer.size() - at);
      if (n <= 0) break;
      at += static_cast<std::size_t>(n);
    }
    ::_exit(0);
  }
  ::close(pipe_fds[1]);
  std::string answer;
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(pipe_fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    answer.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(pipe_fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (WIFSIGNALED(status)) return "child killed by signal " + std::to_string(WTERMSIG(status));
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    return "child exited with " + std::to_string(WEXITSTATUS(status)) + ": " + answer;
  return answer;
}

}  // namespace bounce::test
