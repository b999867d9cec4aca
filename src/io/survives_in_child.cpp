// survives_in_child.hpp.
#include "io/survives_in_child.hpp"

#include <algorithm>
#include <cerrno>
#include <thread>

#if defined(__unix__)
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#endif

namespace lfcam::io {

ChildOutcome survivesInChild(const std::function<void()>& work, std::chrono::milliseconds timeout) {
#if defined(__unix__)
  const pid_t child = fork();
  if (child < 0) return ChildOutcome::Survived;  // no process to spare: the caller goes on unguarded
  if (child == 0) {
    // A crash report from here would look like the caller's own.
    const int devNull = open("/dev/null", O_WRONLY);
    if (devNull >= 0) dup2(devNull, STDERR_FILENO);
    work();
    _exit(0);
  }
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  auto pause = std::chrono::microseconds(200);
  for (;;) {
    int status = 0;
    const pid_t done = waitpid(child, &status, WNOHANG);
    if (done == child)
      return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? ChildOutcome::Survived : ChildOutcome::Crashed;
    if (done < 0 && errno == EINTR) continue;
    if (done < 0) return ChildOutcome::Crashed;
    if (std::chrono::steady_clock::now() >= deadline) {
      kill(child, SIGKILL);
      waitpid(child, &status, 0);
      return ChildOutcome::TimedOut;
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(20000));
  }
#else
  (void)work, (void)timeout;
  return ChildOutcome::Survived;
#endif
}

}  // namespace lfcam::io
