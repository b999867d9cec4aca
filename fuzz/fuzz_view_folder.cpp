// Sub-aperture view folders (HCI input_CamNNN.png with parameters.cfg, NAME_RR_CC.png): the input
// is a folder in the format of fuzz_support.hpp.
#include "fuzz_support.hpp"
#include "lfcam/io/light_field_io.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) { return lfcam::fuzz::initialize(); }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lfcam::fuzz::withTempFolder(data, size, [](const auto& folder) {
    (void)lfcam::probeLightField(folder);
    (void)lfcam::readLightField(folder);
  });
  return 0;
}
