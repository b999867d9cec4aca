// Camera JSON (camera_model.hpp): parsed over the paper's prototype, validated, and asked for its
// microlens lattice as the simulator and calibration would.
#include <nlohmann/json.hpp>

#include "fuzz_support.hpp"
#include "lfcam/simulate/camera_model.hpp"
#include "simulate/camera_json.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) { return lfcam::fuzz::initialize(); }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto json = nlohmann::json::parse(data, data + size, nullptr, false);
  if (json.is_discarded()) return 0;
  auto camera = lfcam::cameraFromJson(json, lfcam::CameraModel::paperPrototype(), "camera.json");
  if (!camera || !camera->validate("camera.json")) return 0;
  if (camera->microlenses) {
    const auto counts = camera->microlensCounts();
    (void)camera->microlensCentreMm(0, 0);
    (void)camera->microlensImageCentrePx(counts[0] - 1, counts[1] - 1);
  }
  return 0;
}
