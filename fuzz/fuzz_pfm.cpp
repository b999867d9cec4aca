// PFM reader (header, then pixels).
#include "fuzz_support.hpp"
#include "lfcam/io/image_io.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) { return lfcam::fuzz::initialize(); }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lfcam::fuzz::withTempFile(data, size, ".pfm", [](const auto& path) {
    (void)lfcam::readImageHeader(path);
    (void)lfcam::readImage(path);
  });
  return 0;
}
