// The one HDF5 lock of the library (hdf5_lock.hpp).
#include "core/hdf5_lock.hpp"

namespace lfcam::hdf5 {

std::mutex& libraryMutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace lfcam::hdf5
