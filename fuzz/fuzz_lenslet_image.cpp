// Lenslet (macro-pixel) images: the image readers (lfcam's PNG structure check, libpng, libtiff, ...), the
// description that gives the view count, and the macro-pixel period estimate.
#include "fuzz_support.hpp"
#include "lfcam/io/light_field_io.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) { return lfcam::fuzz::initialize(); }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // The extension follows the content, as a user's file would be named.
  const bool tiff = size >= 2 && ((data[0] == 'I' && data[1] == 'I') || (data[0] == 'M' && data[1] == 'M'));
  lfcam::fuzz::withTempFile(data, size, tiff ? ".tif" : ".png", [](const auto& path) {
    (void)lfcam::probeLightField(path);
    (void)lfcam::readLightField(path);
  });
  return 0;
}
