// Running a fragile third-party parser on an untrusted file in a throwaway process first.
// libhdf5 1.10 is not hardened against hostile files: fuzzing found a heap overflow and a
// use-after-free inside it on corrupt metadata, which no check in lfcam's own code can prevent.
// A forked child makes the same calls first; if it dies (signal, sanitizer report, or no answer in
// time), the caller refuses the file with a clean error instead of crashing its own process.
#pragma once

#include <chrono>
#include <functional>

namespace lfcam::io {

enum class ChildOutcome { Survived, Crashed, TimedOut };

// Runs `work` in a forked copy of this process, with its stderr silenced, and waits at most
// `timeout`. The child never returns: it ends with _exit (no destructors, no atexit handlers), so
// `work` may use whatever the caller holds, including locks taken before the call. Where fork is
// unavailable, `work` is not run and the outcome is Survived.
ChildOutcome survivesInChild(const std::function<void()>& work, std::chrono::milliseconds timeout);

// True in a build whose runtime leaves a lock out of reach across fork: clang < 18's
// AddressSanitizer, whose quarantine lock (taken when a thread's freed memory joins the global
// quarantine) no entry point lets lfcam hold. A child forked while another thread holds it waits
// for ever and ends TimedOut, a good file refused: rare, and only in sanitized builds.
bool childMayWaitOnALockHeldAtFork();

}  // namespace lfcam::io
