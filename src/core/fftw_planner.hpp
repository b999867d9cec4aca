// FFTW's planner is not thread-safe: every module that plans takes this one lock (a lock per module
// would still let two modules plan at once). Also the deleter for fftwf_malloc'ed buffers.
#pragma once

#include <mutex>

#include <fftw3.h>

namespace lfcam::fftw {

std::mutex& plannerMutex();

struct Free {
  void operator()(void* p) const { fftwf_free(p); }
};

}  // namespace lfcam::fftw
