// Lytro calibration data as `lfcam whites index` finds it (lytro_caldata.hpp): a folder of MOD_*.RAW
// and .TXT pairs, tar archives (libarchive) and backup volumes, each white described and read.
#include "fuzz_support.hpp"
#include "raw_io/lytro_caldata.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) { return lfcam::fuzz::initialize(); }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lfcam::fuzz::withTempFolder(data, size, [](const auto& folder) {
    auto listing = lfcam::findCaldataWhites(folder);
    if (!listing) return;
    for (const lfcam::CaldataWhite& white : listing->whites)
      if (lfcam::describeCaldataWhite(white)) (void)lfcam::readCaldataWhite(white);
  });
  return 0;
}
