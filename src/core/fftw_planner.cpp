// The one FFTW planner lock of the library (fftw_planner.hpp).
#include "core/fftw_planner.hpp"

namespace lfcam::fftw {

std::mutex& plannerMutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace lfcam::fftw
