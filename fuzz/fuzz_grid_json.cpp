// Lenslet grid JSON (lenslet_grid.hpp gridFromJson), written by calibration and read by decode.
#include <nlohmann/json.hpp>

#include "calibrate/grid_json.hpp"
#include "fuzz_support.hpp"
#include "lfcam/calibrate/lenslet_grid.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) { return lfcam::fuzz::initialize(); }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto json = nlohmann::json::parse(data, data + size, nullptr, false);
  if (json.is_discarded()) return 0;
  auto grid = lfcam::gridFromJson(json, "grid.json");
  if (grid) (void)lfcam::gridToJson(*grid);
  return 0;
}
