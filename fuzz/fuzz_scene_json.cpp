// Scene JSON (scene.hpp), then every texture evaluated over its plane and the camera checked, as
// the simulator would.
#include "fuzz_support.hpp"
#include "lfcam/simulate/scene.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) { return lfcam::fuzz::initialize(); }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  auto scene = lfcam::parseScene(text, "scene.json", lfcam::fuzz::scratchFolder() / "no-such-folder");
  if (!scene) return 0;
  (void)scene->camera.validate("scene.json");
  for (const lfcam::Plane& plane : scene->planes)
    for (double fx : {0.0, 0.3, 0.999})
      for (double fy : {0.0, 0.5, 0.999})
        (void)plane.texture.evaluate(fx * plane.widthMm, fy * plane.heightMm, plane.widthMm, plane.heightMm);
  return 0;
}
