// Total focus of a full-size focused plenoptic capture (issue 50, item 6): the virtual depth map
// (focused_depth.hpp) and the photograph rendered at it (focused_render.hpp), as `lfcam edof` of a
// focused capture does, each timed and their sum given as a ratio to the memory floor of reading
// the capture once (memory_floor.hpp: its float samples, 4080 x 3068 x 1, measured before each run).
//
// The capture is simulated, not synthesised: the tests' Galilean three-lens-type hexagonal camera
// (tests/focused_camera.hpp) at 4080 x 3068 with Raytrix-like micro-images 35 pixels across, over
// textured planes at virtual depths 3.2, 4.6 and 6, at 4 samples per pixel (about a minute, outside
// the timing); its ideal all-in-focus photograph gives the PSNR, its virtual depths the map's BadPix.
//
// Run: build/bench/focused_render_bench [runs, default 5]   (times are medians over the runs)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "core/memory_floor.hpp"
#include "focused_camera.hpp"
#include "lfcam/focused/focused_depth.hpp"
#include "lfcam/focused/focused_render.hpp"

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  using namespace lfcam;
  const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  const test::FocusedCameraSpec spec{.width = 4080, .height = 3068, .micro = 35};
  const double pixelsPerLens = 9;  // lfcam edof's choice: a quarter of the micro-image diameter, rounded
  auto start = std::chrono::steady_clock::now();
  const test::FocusedCapture c = test::simulateFocused(spec, {3.2, 4.6, 6.0}, pixelsPerLens, 4);
  std::printf("simulated %dx%d, D = %.2f px, %zu lens types: %.1f s\n", c.image.width(), c.image.height(),
              c.calibration.diameterPx(), c.calibration.lensTypes.size(), secondsSince(start));

  MemoryFloor floor(double(c.image.pixels().size() * sizeof(float)));
  std::vector<double> floors, depthSeconds, renderSeconds, totalSeconds, ratios;
  Image photo, virtualDepth;
  for (int run = 0; run < runs; ++run) {
    floors.push_back(floor.measure());
    start = std::chrono::steady_clock::now();
    FocusedDepthRequest depthRequest;
    depthRequest.pixelsPerLens = pixelsPerLens;
    auto depth = estimateFocusedDepth(c.image, c.calibration, depthRequest);
    depthSeconds.push_back(secondsSince(start));
    if (!depth) return std::fprintf(stderr, "%s\n", depth.error().message.c_str()), 1;
    const auto renderStart = std::chrono::steady_clock::now();
    FocusedRenderRequest request;
    request.pixelsPerLens = pixelsPerLens;
    request.virtualDepthMap = &depth->virtualDepth;
    auto rendered = renderFocused(c.image, c.calibration, request);
    renderSeconds.push_back(secondsSince(renderStart));
    totalSeconds.push_back(secondsSince(start));
    if (!rendered) return std::fprintf(stderr, "%s\n", rendered.error().message.c_str()), 1;
    photo = std::move(rendered).value();
    virtualDepth = std::move(depth->virtualDepth);
    ratios.push_back(totalSeconds.back() / floors.back());
  }
  std::printf(
      "total focus %dx%d, medians of %d runs: depth %.3f s, render %.3f s, total %.3f s; floor %.2f ms; "
      "ratio %.0f\n",
      photo.width(), photo.height(), runs, medianOf(depthSeconds), medianOf(renderSeconds), medianOf(totalSeconds),
      medianOf(floors) * 1e3, medianOf(ratios));
  const test::VirtualDepthScore depthScore =
      test::scoreVirtualDepth(virtualDepth, c.truth.virtualDepth, c.calibration.diameterPx(), int(pixelsPerLens));
  std::printf(
      "PSNR against the ideal photograph: %.2f dB; depth: BadPix(0.25 px) %.2f %%, relative error in v %.2f %%\n",
      test::psnr(photo, c.truth.allInFocus, int(pixelsPerLens)), 100 * depthScore.badPix,
      100 * depthScore.relativeError);
  return 0;
}
