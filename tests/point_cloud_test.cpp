// Depth in millimetres and as a point cloud, against the simulator's exact depth: the `people`
// scene (cards at four distances) seen by a small plenoptic camera (people_camera.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "lfcam/edof/depth.hpp"
#include "lfcam/edof/point_cloud.hpp"
#include "lfcam/simulate/scene.hpp"
#include "lfcam/simulate/simulate.hpp"
#include "people_camera.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

class MetricDepth : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const CameraModel camera = test::peopleCamera();
    scene_ = new Scene(*builtinScene("people", camera));
    auto lightField = idealLightField(*scene_, camera);
    ASSERT_TRUE(lightField) << lightField.error().message;
    lightField_ = new LightField(std::move(*lightField));
    auto depth = idealDepth(*scene_, camera);
    ASSERT_TRUE(depth) << depth.error().message;
    exactMm_ = new Image(std::move(*depth));
  }
  static void TearDownTestSuite() {
    delete scene_;
    delete lightField_;
    delete exactMm_;
  }
  // The card whose plane `distanceMm` lies on, or nullptr.
  static const Plane* cardAt(double distanceMm) {
    for (const Plane& plane : scene_->planes)
      if (std::abs(distanceMm - plane.centreMm[2]) < 1e-3) return &plane;
    return nullptr;
  }
  static Scene* scene_;
  static LightField* lightField_;
  static Image* exactMm_;
};
Scene* MetricDepth::scene_ = nullptr;
LightField* MetricDepth::lightField_ = nullptr;
Image* MetricDepth::exactMm_ = nullptr;

// The estimated disparity, in mm: each card's median distance lies between the distances of its
// exact disparity +-0.07 (the benchmark's BadPix threshold; 7 % of the distance on the 10 m backdrop).
TEST_F(MetricDepth, EstimatedDistancesMatchTheSimulatorsDepth) {
  auto depth = estimateDepth(*lightField_);
  ASSERT_TRUE(depth) << depth.error().message;
  auto distance = distanceMap(lightField_->metadata, depth->disparity);
  ASSERT_TRUE(distance) << distance.error().message;
  for (const Plane& card : scene_->planes) {
    std::vector<float> seen;
    for (std::size_t i = 0; i < distance->planeSize(); ++i)
      if (cardAt(exactMm_->plane(0)[i]) == &card) seen.push_back(distance->plane(0)[i]);
    if (seen.size() < 50) continue;  // hidden
    std::nth_element(seen.begin(), seen.begin() + seen.size() / 2, seen.end());
    const double median = seen[seen.size() / 2];
    const Optics& optics = *lightField_->metadata.optics;
    const double exact = *disparityFromDistance(optics, card.centreMm[2]);
    const double nearest = *distanceFromDisparity(optics, exact + 0.07),
                 farthest = *distanceFromDisparity(optics, exact - 0.07);
    std::printf("people 9x9x80x80, %s at %.0f mm: median distance %.0f mm over %zu pixels (%.0f to %.0f allowed)\n",
                card.name.c_str(), card.centreMm[2], median, seen.size(), nearest, farthest);
    EXPECT_GT(median, nearest) << card.name;
    EXPECT_LT(median, farthest) << card.name;
  }
}

// From the exact disparity, every point seen on a card lies on that card: at its distance and
// within its rectangle (a pixel's footprint of slack), in the scene's frame.
TEST_F(MetricDepth, PointsFromTheExactDisparityLieOnTheCards) {
  const Optics& optics = *lightField_->metadata.optics;
  Image disparity(exactMm_->width(), exactMm_->height(), 1), confidence(disparity.width(), disparity.height(), 1);
  for (std::size_t i = 0; i < disparity.planeSize(); ++i) {
    disparity.plane(0)[i] = float(disparityFromDistance(optics, exactMm_->plane(0)[i]).value_or(NAN));
    confidence.plane(0)[i] = 1.0f;
  }
  auto cloud = pointCloudFromDepth(*lightField_, disparity, confidence);
  ASSERT_TRUE(cloud) << cloud.error().message;
  ASSERT_GT(cloud->positions.size(), disparity.planeSize() / 2);
  int onCards = 0;
  for (const auto& point : cloud->positions) {
    const Plane* card = cardAt(point[2]);
    if (!card) continue;
    ++onCards;
    const double slack = point[2] * optics.spatialStepMm / optics.lensToMicrolensMm;
    EXPECT_LE(std::abs(point[0] - card->centreMm[0]), card->widthMm / 2 + slack) << card->name;
    EXPECT_LE(std::abs(point[1] - card->centreMm[1]), card->heightMm / 2 + slack) << card->name;
  }
  EXPECT_GT(onCards, int(cloud->positions.size()) * 9 / 10);

  // Unsure points are left out.
  for (int t = 0; t < confidence.height() / 2; ++t)
    for (int s = 0; s < confidence.width(); ++s) confidence.at(s, t, 0) = 0.2f;
  auto sure = pointCloudFromDepth(*lightField_, disparity, confidence, 0.5);
  ASSERT_TRUE(sure);
  EXPECT_LT(sure->positions.size(), cloud->positions.size() * 6 / 10);
  for (float c : sure->confidences) EXPECT_GE(c, 0.5f);
}

TEST_F(MetricDepth, PlyFileReadsBack) {
  PointCloud cloud;
  cloud.positions = {{1.5f, -2.0f, 900.0f}, {0.0f, 0.0f, 1000.0f}};
  cloud.colors = {{255, 0, 10}, {1, 2, 3}};
  cloud.confidences = {0.25f, 1.0f};
  test::TempDir dir;
  ASSERT_TRUE(writePly(dir / "c.ply", cloud));
  std::ifstream in(dir / "c.ply", std::ios::binary);
  std::stringstream content;
  content << in.rdbuf();
  const std::string bytes = content.str();
  const std::size_t end = bytes.find("end_header\n");
  ASSERT_NE(end, std::string::npos);
  const std::string header = bytes.substr(0, end);
  for (const char* line : {"format binary_little_endian 1.0", "element vertex 2", "property float x",
                           "property uchar red", "property float confidence"})
    EXPECT_NE(header.find(line), std::string::npos) << line;
  const std::size_t body = end + std::strlen("end_header\n");
  ASSERT_EQ(bytes.size(), body + 2 * 19);
  float x = 0, confidence = 0;
  std::memcpy(&x, bytes.data() + body, 4);  // the test machines are little-endian
  std::memcpy(&confidence, bytes.data() + body + 15, 4);
  EXPECT_EQ(x, 1.5f);
  EXPECT_EQ(std::uint8_t(bytes[body + 12]), 255);
  EXPECT_EQ(confidence, 0.25f);

  // A missing folder: an error naming the file, and nothing written.
  auto failed = writePly(dir / "missing" / "c.ply", cloud);
  ASSERT_FALSE(failed);
  EXPECT_NE(failed.error().message.find("c.ply"), std::string::npos) << failed.error().message;
  EXPECT_FALSE(fs::exists(dir / "missing"));

  // Maps of another size, or no optics: usage errors.
  Image small(3, 3, 1);
  EXPECT_FALSE(pointCloudFromDepth(*lightField_, small, small));
}

}  // namespace
}  // namespace lfcam
