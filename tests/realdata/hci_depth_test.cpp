// Depth and all-in-focus on the real HCI benchmark scene "antinous" (9x9 views of 512x512), scored
// against its ground-truth disparity as the benchmark scores (disparity_scores.hpp: BadPix, MSE
// x100, bumpiness; 15-pixel border left out). Antinous is held out: the depth defaults are chosen
// on the development scenes of bench/depth_scenes.hpp, never on this scene; it checks that they
// hold on a scene they were not tuned on.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include "io/hci_parameters.hpp"
#include "lfcam/edof/all_in_focus.hpp"
#include "lfcam/edof/depth.hpp"
#include "lfcam/edof/disparity_scores.hpp"
#include "lfcam/edof/point_cloud.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "lfcam/render/refocus.hpp"
#include "sharpness.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

// The scene's light field and ground-truth disparity, or the test skipped without the data.
class HciAntinousDepth : public ::testing::Test {
 protected:
  void SetUp() override {
    LFCAM_REQUIRE_SHARED_DATA("hci-antinous", folder);
    dir = folder;
    auto read = readLightField(dir);
    ASSERT_TRUE(read) << read.error().message;
    lightField.emplace(std::move(*read));
    auto readTruth = readImage(dir / "gt_disp_lowres.pfm");
    ASSERT_TRUE(readTruth) << readTruth.error().message;
    truth.emplace(std::move(*readTruth));
  }
  std::filesystem::path dir;
  std::optional<LightField> lightField;
  std::optional<Image> truth;
};

TEST_F(HciAntinousDepth, ScoresAndAllInFocus) {
  // parameters.cfg gives the optics (hci_parameters.hpp): disparity 0 is the focus distance, 7 m.
  ASSERT_TRUE(lightField->metadata.optics);
  EXPECT_NEAR(*distanceFromDisparity(*lightField->metadata.optics, 0.0), 7000.0, 1e-6);

  auto depth = estimateDepth(*lightField);
  ASSERT_TRUE(depth) << depth.error().message;
  auto scores = scoreHci(depth->disparity, *truth);
  ASSERT_TRUE(scores) << scores.error().message;
  long planar = 0;
  const Image planes = planarMask(*truth);  // named: a range-for over a temporary's pixels() reads freed memory
  for (float p : planes.pixels()) planar += p != 0.0f;
  std::printf(
      "hci-antinous (held out): BadPix(0.07) %.2f %%, BadPix(0.03) %.2f %%, MSE x100 %.3f, bumpiness %.3f "
      "on planes (%.1f %% of the image)\n",
      scores->badPix007, scores->badPix003, scores->mse100, scores->bumpiness,
      100.0 * double(planar) / double(truth->width() * truth->height()));
  // Held out: no setting's value was chosen on it (the view offsets' step was shaped while its score
  // was printed beside the development scenes; design.md, "Tuning protocol"). Measured 4.44 % and
  // MSE x100 6.30 with today's defaults (`build/bench/depth_bench` prints every scene's table; other
  // processors read up to 0.15 point apart); the goal is 5 %, and the history of the figure is in git.
  EXPECT_LT(scores->badPix007, 5.0);
  EXPECT_LT(scores->mse100, 7.5);

  // In millimetres: the estimate against the ground truth, both converted with parameters.cfg.
  auto distance = distanceMap(lightField->metadata, depth->disparity);
  auto truthMm = distanceMap(lightField->metadata, *truth);
  ASSERT_TRUE(distance && truthMm);
  std::vector<double> errors;
  for (std::size_t i = 0; i < truthMm->planeSize(); ++i)
    errors.push_back(std::abs(distance->plane(0)[i] / truthMm->plane(0)[i] - 1.0));
  std::sort(errors.begin(), errors.end());
  std::printf("hci-antinous distance error: median %.2f %%, 90th percentile %.2f %%\n", 100 * errors[errors.size() / 2],
              100 * errors[errors.size() * 9 / 10]);
  EXPECT_LT(errors[errors.size() / 2], 0.01);

  // The all-in-focus photograph from that depth: as sharp as the sharpest of the photographs
  // focused on the nearest (the face) and the farthest (the wall) part, in both.
  auto photo = allInFocus(*lightField, {.disparity = &depth->disparity});
  ASSERT_TRUE(photo) << photo.error().message;
  const Image nearFocus = refocus(*lightField, 2.0), farFocus = refocus(*lightField, -2.6);
  struct Window {
    const char* name;
    int x0, y0, x1, y1;
  } windows[] = {{"hair (near)", 200, 60, 300, 120}, {"wall (far)", 400, 20, 490, 100}};
  for (const Window& w : windows) {
    const double all = test::laplacianVariance(photo->photo, w.x0, w.y0, w.x1, w.y1);
    const double nearSharpness = test::laplacianVariance(nearFocus, w.x0, w.y0, w.x1, w.y1);
    const double farSharpness = test::laplacianVariance(farFocus, w.x0, w.y0, w.x1, w.y1);
    std::printf("%s: all-in-focus %.3g, focused near %.3g, focused far %.3g\n", w.name, all, nearSharpness,
                farSharpness);
    EXPECT_GT(all, 0.9 * std::max(nearSharpness, farSharpness)) << w.name;
  }
}

// The ground-truth disparity in millimetres (depth.hpp, distanceMap, with the optics that
// hci_parameters.hpp derives) is the benchmark toolkit's depth: 1 / z = 1 / focus + 1000 sensor d /
// (baseline f max(w, h)), z in m; and its point cloud is the centre camera's pinhole projection.
TEST_F(HciAntinousDepth, GroundTruthInMillimetresAndAsPoints) {
  auto parameters = readHciParameters(dir / "parameters.cfg");
  ASSERT_TRUE(parameters) << parameters.error().message;
  const double size = std::max(*parameters->imageWidth, *parameters->imageHeight);
  auto distance = distanceMap(lightField->metadata, *truth);
  ASSERT_TRUE(distance) << distance.error().message;
  double worst = 0, nearest = INFINITY, farthest = 0;
  for (std::size_t i = 0; i < distance->planeSize(); ++i) {
    const double d = truth->plane(0)[i];
    const double toolkitM =
        1.0 / (1.0 / *parameters->focusDistanceM +
               1000.0 * *parameters->sensorSizeMm * d / (*parameters->baselineMm * *parameters->focalLengthMm * size));
    worst = std::max(worst, std::abs(distance->plane(0)[i] / (1000.0 * toolkitM) - 1.0));
    nearest = std::min(nearest, 1000.0 * toolkitM), farthest = std::max(farthest, 1000.0 * toolkitM);
  }
  std::printf("hci-antinous ground truth: %.0f to %.0f mm, largest relative difference from the toolkit's %.2g\n",
              nearest, farthest, worst);
  EXPECT_LT(worst, 1e-5);

  Image sure(truth->width(), truth->height(), 1);
  for (float& c : sure.pixels()) c = 1.0f;
  auto cloud = pointCloudFromDepth(*lightField, *truth, sure);
  ASSERT_TRUE(cloud) << cloud.error().message;
  ASSERT_EQ(cloud->positions.size(), distance->planeSize());  // every pixel nearer than infinity
  // The top-left pixel: x = (0.5 - w / 2) pixel z / f, pixel = sensor / max(w, h), f the focal length.
  const double pixelMm = *parameters->sensorSizeMm / size, z = distance->plane(0)[0];
  EXPECT_NEAR(cloud->positions[0][0], (0.5 - 0.5 * truth->width()) * pixelMm * z / *parameters->focalLengthMm,
              1e-3 * z);
  EXPECT_NEAR(cloud->positions[0][1], (0.5 - 0.5 * truth->height()) * pixelMm * z / *parameters->focalLengthMm,
              1e-3 * z);
  EXPECT_NEAR(cloud->positions[0][2], z, 1e-3 * z);
}

}  // namespace
}  // namespace lfcam
