// The HDF5 library (Debian's serial build) is not thread-safe: every module that calls it takes
// this one lock (a lock per module would still let two modules call it at once).
#pragma once

#include <mutex>

namespace lfcam::hdf5 {

std::mutex& libraryMutex();

}  // namespace lfcam::hdf5
