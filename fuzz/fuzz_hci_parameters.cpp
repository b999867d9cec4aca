// The HCI benchmark's parameters.cfg: parsed alone (hci_parameters.hpp), then read as part of a
// small valid folder of 2 x 2 views.
#include "fuzz_support.hpp"
#include "io/hci_parameters.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/io/light_field_io.hpp"

namespace {
std::filesystem::path viewFolder() {
  static const std::filesystem::path folder = [] {
    const auto f = lfcam::fuzz::scratchFolder() / "hci";
    std::filesystem::create_directories(f);
    lfcam::Image view(4, 4, 3);
    for (int i = 0; i < 4; ++i) (void)lfcam::writeImage(f / ("input_Cam00" + std::to_string(i) + ".png"), view);
    return f;
  }();
  return folder;
}
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) { return lfcam::fuzz::initialize(); }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  if (auto parameters = lfcam::parseHciParameters(text)) (void)lfcam::hciOptics(*parameters);
  const auto folder = viewFolder();
  lfcam::fuzz::writeBytes(folder / "parameters.cfg", text);
  (void)lfcam::probeLightField(folder);
  (void)lfcam::readLightField(folder);
  return 0;
}
