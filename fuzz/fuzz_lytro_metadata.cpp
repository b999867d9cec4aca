// Lytro frame metadata JSON (both real layouts, wrapped or not), and the camera setting in it.
#include <nlohmann/json.hpp>

#include "fuzz_support.hpp"
#include "raw_io/lytro_metadata.hpp"
#include "raw_io/lytro_setting.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) { return lfcam::fuzz::initialize(); }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto json = nlohmann::json::parse(data, data + size, nullptr, false);
  if (json.is_discarded()) return 0;
  const nlohmann::json* frame = lfcam::findLytroFrameMetadata(json);
  (void)lfcam::parseLytroFrameMetadata(frame ? *frame : json, "fuzz.json");
  (void)lfcam::lytroCameraSetting(json, nullptr);
  return 0;
}
