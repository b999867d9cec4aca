// readRaw: Lytro containers, PNG/TIFF lenslet images and camera raws (LibRaw), recognised by
// content; the file is named as a user's would be.
#include <cstring>

#include "fuzz_support.hpp"
#include "lfcam/raw_io/raw_io.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) { return lfcam::fuzz::initialize(); }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto startsWith = [&](const char* magic) {
    return size >= std::strlen(magic) && std::memcmp(data, magic, std::strlen(magic)) == 0;
  };
  const char* extension = startsWith("\x89LFP")                    ? ".lfp"
                          : startsWith("\x89PNG")                  ? ".png"
                          : (startsWith("II") || startsWith("MM")) ? ".tif"
                                                                   : ".dng";
  lfcam::fuzz::withTempFile(data, size, extension,
                            [](const auto& path) { (void)lfcam::readRaw(path, {.useCameraJson = false}); });
  return 0;
}
