// Virtual depth and total focus of a focused plenoptic camera against the simulator's truth, scene
// by scene (issue 50, items 3 and 4): the tests' Galilean three-type hexagonal camera
// (tests/focused_camera.hpp: 640 x 480, 20 px micro-images, types sharp near v = 3, 4.5 and 7) at
// 5 photograph pixels per micro-image, 16 samples per pixel, before
//   layers          value noise at v = 3.2 (background), 4.6 and 6 (two cards);
//   slant           one value-noise plane at v = 4.2 turned 75 degrees about its vertical axis;
//   fine texture    a plane at v = 4.2 whose features are 1.5 photograph pixels;
//   weak texture    the same plane at 4 pixels, its contrast 0.45 to 0.55;
//   layers, noisy   the layers with photon noise, 1000 electrons at the white's brightest pixel.
// Per scene: BadPix (disparity D / v off by more than 0.25 image pixels) and the mean relative
// error in v of the estimated map; PSNR of the total focus against the ideal all-in-focus image
// (and of the total focus rendered at the true virtual depths: what rendering alone gives);
// the seam energy (seam_energy.hpp) of the total focus and of fixed patches at the scene's median v,
// each over the ideal's, and that of their error (the rendering less the ideal: test::seamError),
// which is 0 for the ideal itself. Margins of one micro-image are left out.
//
// Run: build/bench/focused_scenes_bench   (about a minute on 2 cores)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "focused_camera.hpp"
#include "lfcam/focused/focused_depth.hpp"
#include "lfcam/focused/focused_render.hpp"
#include "lfcam/focused/seam_energy.hpp"

namespace {

using namespace lfcam;

constexpr double kPixelsPerLens = test::kFocusedPixelsPerLens;

struct NamedScene {
  const char* name;
  Scene scene;
  double electronsAtWhite = 0;
};

double median(std::vector<float> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

}  // namespace

int main() {
  const CameraModel camera = test::focusedCamera();
  std::vector<NamedScene> scenes;
  scenes.push_back({"layers", test::focusedLayers(camera, {3.2, 4.6, 6.0}, kPixelsPerLens)});
  Plane slant = test::focusedPlane(camera, "slant", 4.2, 6, 4, kPixelsPerLens, 4);
  slant.tiltYDeg = 75;
  scenes.push_back({"slant", test::oneSurface(camera, "slant", slant)});
  scenes.push_back(
      {"fine texture",
       test::oneSurface(camera, "fine", test::focusedPlane(camera, "fine", 4.2, 1.6, 1.5, kPixelsPerLens, 5))});
  Plane weak = test::focusedPlane(camera, "weak", 4.2, 1.6, 4, kPixelsPerLens, 6);
  weak.texture.dark = {0.45f, 0.45f, 0.45f};
  weak.texture.light = {0.55f, 0.55f, 0.55f};
  scenes.push_back({"weak texture", test::oneSurface(camera, "weak", weak)});
  scenes.push_back({"layers, noisy", test::focusedLayers(camera, {3.2, 4.6, 6.0}, kPixelsPerLens), 1000});

  std::printf(
      "| scene | v (truth, 5th-95th percentile) | BadPix(0.25 px) %% | relative error in v %% | total focus PSNR dB "
      "| at the true v | seam energy / ideal's: total focus | fixed patches | seam error: total focus | fixed patches "
      "|\n|---|---|---|---|---|---|---|---|---|---|\n");
  for (const NamedScene& s : scenes) {
    const test::FocusedCapture c = test::simulateFocusedScene(camera, s.scene, kPixelsPerLens, 16, s.electronsAtWhite);
    const int margin = int(kPixelsPerLens);
    FocusedDepthRequest depthRequest;
    depthRequest.pixelsPerLens = kPixelsPerLens;
    auto depth = estimateFocusedDepth(c.image, c.calibration, depthRequest);
    if (!depth) {
      std::fprintf(stderr, "%s: %s\n", s.name, depth.error().message.c_str());
      return 1;
    }
    const test::VirtualDepthScore score =
        test::scoreVirtualDepth(depth->virtualDepth, c.truth.virtualDepth, c.calibration.diameterPx(), margin);
    FocusedRenderRequest request;
    request.pixelsPerLens = kPixelsPerLens;
    request.virtualDepthMap = &depth->virtualDepth;
    auto totalFocus = renderFocused(c.image, c.calibration, request);
    request.virtualDepthMap = &c.truth.virtualDepth;
    auto trueFocus = renderFocused(c.image, c.calibration, request);
    std::vector<float> truth(c.truth.virtualDepth.pixels().begin(), c.truth.virtualDepth.pixels().end());
    request.virtualDepthMap = nullptr;
    request.virtualDepth = median(truth);
    request.nearestLensOnly = true;
    auto patches = renderFocused(c.image, c.calibration, request);
    for (const auto* photo : {&totalFocus, &trueFocus, &patches})
      if (!*photo) {
        std::fprintf(stderr, "%s: %s\n", s.name, photo->error().message.c_str());
        return 1;
      }
    std::sort(truth.begin(), truth.end());
    const double ideal = seamEnergy(c.truth.allInFocus, c.calibration, kPixelsPerLens);
    std::printf("| %s | %.2f-%.2f | %.2f | %.2f | %.2f | %.2f | %.3f | %.3f | %.3f | %.3f |\n", s.name,
                truth[truth.size() / 20], truth[truth.size() * 19 / 20], 100 * score.badPix, 100 * score.relativeError,
                test::psnr(*totalFocus, c.truth.allInFocus, margin), test::psnr(*trueFocus, c.truth.allInFocus, margin),
                seamEnergy(*totalFocus, c.calibration, kPixelsPerLens) / ideal,
                seamEnergy(*patches, c.calibration, kPixelsPerLens) / ideal,
                test::seamError(*totalFocus, c.truth.allInFocus, c.calibration, kPixelsPerLens),
                test::seamError(*patches, c.truth.allInFocus, c.calibration, kPixelsPerLens));
    std::fflush(stdout);
  }
  return 0;
}
