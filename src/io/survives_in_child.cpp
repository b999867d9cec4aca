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

// clang's AddressSanitizer runtime before LLVM 18 takes none of its own locks around fork: a child
// forked while another thread is inside its allocator waits for ever on that thread's lock (seen:
// `lfcam batch --jobs 2` under ASan, the child stuck in the allocator's refill, reported as a 30 s
// hang of libhdf5). Later runtimes hold these locks across fork themselves; for the older ones,
// lfcam takes the same locks, by the runtime's own functions, as those runtimes do.
#if defined(__clang__) && __clang_major__ < 18 && defined(__has_feature)
#if __has_feature(address_sanitizer)
#define LFCAM_LOCK_ASAN_AROUND_FORK 1
namespace __lsan {
void LockThreadRegistry();
void UnlockThreadRegistry();
void LockAllocator();
void UnlockAllocator();
}  // namespace __lsan
namespace __sanitizer {
void StackDepotLockAll();
void StackDepotUnlockAll();
}  // namespace __sanitizer
#endif
#endif

namespace lfcam::io {

namespace {

#if defined(__unix__)
pid_t forkKeepingAllocatorUsable() {
#if defined(LFCAM_LOCK_ASAN_AROUND_FORK)
  __lsan::LockThreadRegistry();
  __lsan::LockAllocator();
  __sanitizer::StackDepotLockAll();
  const pid_t child = fork();
  __sanitizer::StackDepotUnlockAll();
  __lsan::UnlockAllocator();
  __lsan::UnlockThreadRegistry();
  return child;
#else
  return fork();  // glibc's malloc holds its own locks across fork
#endif
}
#endif

}  // namespace

bool childMayWaitOnALockHeldAtFork() {
#if defined(LFCAM_LOCK_ASAN_AROUND_FORK)
  return true;
#else
  return false;
#endif
}

ChildOutcome survivesInChild(const std::function<void()>& work, std::chrono::milliseconds timeout) {
#if defined(__unix__)
  const pid_t child = forkKeepingAllocatorUsable();
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
