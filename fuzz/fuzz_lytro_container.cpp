// Lytro containers (.lfp, .lfr): sections, SHA-1 names, the JSON table of contents, its
// references, the listing, and the raw frame with its metadata and packed samples.
#include "fuzz_support.hpp"
#include "lfcam/raw_io/raw_io.hpp"
#include "raw_io/lytro_contents.hpp"
#include "raw_io/lytro_raw.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) { return lfcam::fuzz::initialize(); }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  auto container = lfcam::parseLytroContainer({data, size}, "fuzz.lfp");
  if (!container) return 0;
  (void)container->references();
  (void)lfcam::describeLytroContainer(*container);
  (void)lfcam::rawFromLytroContainer(*container, "fuzz.lfp");
  return 0;
}
