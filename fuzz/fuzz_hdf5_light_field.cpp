// HDF5 light-field reader (.lf.h5): probe, then read.
#include "fuzz_support.hpp"
#include "lfcam/io/light_field_io.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) { return lfcam::fuzz::initialize(); }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lfcam::fuzz::withTempFile(data, size, ".lf.h5", [](const auto& path) {
    (void)lfcam::probeLightField(path);
    (void)lfcam::readLightField(path);
  });
  return 0;
}
