// What chose the focused renderer's sampling kernel and lens-type weights (focused_render.cpp):
// total focus rendered at the TRUE virtual depths (so depth estimation plays no part), PSNR against
// the simulator's ideal photograph, on scenes apart from focused_scenes_bench's (texture seeds 21
// and 31, where that bench's are 1-6), through the tests' three-type Galilean camera:
//   features   a plane at v = 4.2 whose value-noise features are 1.5, 2, 3 and 4 photograph pixels;
//   slant      a plane at v = 4.2 turned 75 degrees;
//   planes     planes at v = 2.5, 3, 3.6, 5 and 7 (3 px features) at 2.5, 3.5 and 5 pixels per lens
//              (photograph pixels D / (pixels per lens x v) = 0.6 to 3.2 sensor pixels wide);
//   finer      the 1.5 px features through the same optics with sensor pixels half as wide (the
//              capture's own limit, apart from the renderer's).
//
// Run: build/bench/focused_kernel_bench   (a few minutes on 2 cores)
#include <cstdio>
#include <string>

#include "focused_camera.hpp"
#include "lfcam/focused/focused_render.hpp"

namespace {

using namespace lfcam;

// PSNR of total focus at the true virtual depths of `scene` through `camera`.
double truePsnr(const CameraModel& camera, const Scene& scene, double pixelsPerLens) {
  const test::FocusedCapture c = test::simulateFocusedScene(camera, scene, pixelsPerLens);
  FocusedRenderRequest request;
  request.pixelsPerLens = pixelsPerLens;
  request.virtualDepthMap = &c.truth.virtualDepth;
  auto photo = renderFocused(c.image, c.calibration, request);
  if (!photo) {
    std::fprintf(stderr, "%s: %s\n", scene.name.c_str(), photo.error().message.c_str());
    return 0;
  }
  return test::psnr(*photo, c.truth.allInFocus, int(pixelsPerLens));
}

}  // namespace

int main() {
  const CameraModel camera = test::focusedCamera();
  constexpr double kPixelsPerLens = test::kFocusedPixelsPerLens;
  for (const std::uint64_t seed : {21, 31}) {
    std::printf("seed %llu, %g pixels per lens, PSNR dB at the true v\n", (unsigned long long)seed, kPixelsPerLens);
    std::printf("  features 1.5 / 2 / 3 / 4 px:");
    for (const double feature : {1.5, 2.0, 3.0, 4.0})
      std::printf(" %.2f",
                  truePsnr(camera,
                           test::oneSurface(camera, "features",
                                            test::focusedPlane(camera, "p", 4.2, 1.6, feature, kPixelsPerLens, seed)),
                           kPixelsPerLens));
    Plane slant = test::focusedPlane(camera, "slant", 4.2, 6, 4, kPixelsPerLens, seed + 1);
    slant.tiltYDeg = 75;
    std::printf("\n  slant: %.2f\n", truePsnr(camera, test::oneSurface(camera, "slant", slant), kPixelsPerLens));
    for (const double pixelsPerLens : {2.5, 3.5, 5.0}) {
      std::printf("  planes at v 2.5 / 3 / 3.6 / 5 / 7, %g pixels per lens:", pixelsPerLens);
      for (const double v : {2.5, 3.0, 3.6, 5.0, 7.0})
        std::printf(" %.2f", truePsnr(camera,
                                      test::oneSurface(camera, "plane",
                                                       test::focusedPlane(camera, "p", v, 1.6, 3, pixelsPerLens, seed)),
                                      pixelsPerLens));
      std::printf("\n");
    }
    CameraModel finer = camera;
    finer.sensor.pixelPitchMm /= 2;
    finer.sensor.width *= 2;
    finer.sensor.height *= 2;
    std::printf("  features 1.5 px, sensor pixels half as wide: %.2f\n",
                truePsnr(finer,
                         test::oneSurface(finer, "features",
                                          test::focusedPlane(finer, "p", 4.2, 1.6, 1.5, kPixelsPerLens, seed)),
                         kPixelsPerLens));
    std::fflush(stdout);
  }
  return 0;
}
