// parameters.cfg of the HCI benchmark (hci_parameters.hpp): the keys, the bounds, garbage, and the
// optics that turn disparity into the benchmark's depth.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "io/hci_parameters.hpp"
#include "lfcam/edof/depth.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

// The antinous scene's file, shortened.
const char* kAntinous = R"([intrinsics]
focal_length_mm = 100.0
image_resolution_x_px = 512
image_resolution_y_px = 512
sensor_size_mm = 35.0
fstop = 100.0

[extrinsics]
num_cams_x = 9
num_cams_y = 9
baseline_mm = 100.0
focus_distance_m = 7.0
center_cam_rx_rad = 1.4758878946304321

[meta]
scene = antinous
disp_min = -3.3
disp_max = 2.8
)";

TEST(HciParameters, ReadsTheKeysLfcamUses) {
  auto p = parseHciParameters(kAntinous);
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_EQ(p->imageWidth, 512);
  EXPECT_EQ(p->imageHeight, 512);
  EXPECT_EQ(p->camerasX, 9);
  EXPECT_EQ(p->camerasY, 9);
  EXPECT_DOUBLE_EQ(*p->focalLengthMm, 100);
  EXPECT_DOUBLE_EQ(*p->sensorSizeMm, 35);
  EXPECT_DOUBLE_EQ(*p->baselineMm, 100);
  EXPECT_DOUBLE_EQ(*p->focusDistanceM, 7);
  EXPECT_DOUBLE_EQ(*p->disparityMin, -3.3);
  EXPECT_DOUBLE_EQ(*p->disparityMax, 2.8);
  EXPECT_EQ(p->scene, "antinous");
  // Missing keys stay unknown, and without them there are no optics.
  auto partial = parseHciParameters("num_cams_x = 3\nnum_cams_y = 3\n");
  ASSERT_TRUE(partial);
  EXPECT_FALSE(partial->focalLengthMm);
  EXPECT_FALSE(hciOptics(*partial));
}

TEST(HciParameters, OpticsGiveTheBenchmarksDepth) {
  auto p = parseHciParameters(kAntinous);
  ASSERT_TRUE(p);
  auto optics = hciOptics(*p);
  ASSERT_TRUE(optics);
  for (double d : {-3.3, -1.0, -0.2, 0.0, 0.5, 2.8}) {
    // The toolkit's disp2depth (scenes/base_scene.py), in metres.
    const double q = 100.0 * 100.0 * 512;
    const double benchmark = 1.0 / ((1000.0 * 35.0) * d / q + 1.0 / 7.0);
    auto z = distanceFromDisparity(*optics, d);
    ASSERT_TRUE(z);
    EXPECT_NEAR(*z / 1000.0, benchmark, 1e-9 * benchmark) << "disparity " << d;
    auto back = disparityFromDistance(*optics, *z);
    ASSERT_TRUE(back);
    EXPECT_NEAR(*back, d, 1e-9) << "disparity " << d;
  }
  EXPECT_NEAR(*distanceFromDisparity(*optics, 0.0), 7000.0, 1e-6);  // the focus plane
}

TEST(HciParameters, OpticsSurviveAnHciFolder) {
  auto p = parseHciParameters(kAntinous);
  ASSERT_TRUE(p);
  LightField lf({.nu = 3, .nv = 3, .ns = 8, .nt = 6, .channels = 3});
  lf.metadata.optics = hciOptics(*p);
  test::TempDir dir;
  ASSERT_TRUE(writeLightField(dir / "hci", lf));
  auto back = readLightField(dir / "hci");
  ASSERT_TRUE(back) << back.error().message;
  ASSERT_TRUE(back->metadata.optics);
  const Optics &a = *lf.metadata.optics, &b = *back->metadata.optics;
  EXPECT_NEAR(b.lensStepMm, a.lensStepMm, 1e-9);
  EXPECT_NEAR(b.spatialStepMm, a.spatialStepMm, 1e-12);
  EXPECT_NEAR(b.lensToMicrolensMm, a.lensToMicrolensMm, 1e-9);
  EXPECT_NEAR(*b.focalLengthMm, *a.focalLengthMm, 1e-9);
}

TEST(HciParameters, RefusesBadValuesNamingTheLine) {
  struct Case {
    const char* text;
    const char* expected;  // in the message
  };
  const Case cases[] = {
      {"num_cams_x = nine\n", "line 1: num_cams_x"},
      {"# c\nnum_cams_x = 0\n", "line 2: num_cams_x"},
      {"num_cams_x = 2.5\n", "out of range"},
      {"num_cams_y = 1e9\n", "out of range"},
      {"focal_length_mm = -100\n", "focal_length_mm"},
      {"focus_distance_m = nan\n", "not a number"},
      {"disp_min = inf\n", "not a number"},
      {"image_resolution_x_px = 512px\n", "not a number"},
      {"just some words\n", "expected 'key = value'"},
      {"= 3\n", "expected 'key = value'"},
  };
  for (const Case& c : cases) {
    auto p = parseHciParameters(c.text, "scene/parameters.cfg");
    ASSERT_FALSE(p) << c.text;
    EXPECT_EQ(p.error().code, ErrorCode::Format);
    EXPECT_NE(p.error().message.find("scene/parameters.cfg: "), std::string::npos) << p.error().message;
    EXPECT_NE(p.error().message.find(c.expected), std::string::npos) << p.error().message;
    EXPECT_EQ(p.error().message.find('\n'), std::string::npos);
  }
  EXPECT_FALSE(parseHciParameters(std::string(5000, 'x')));           // a line too long
  EXPECT_FALSE(parseHciParameters(std::string((1 << 20) + 1, '#')));  // a file too big
  EXPECT_FALSE(readHciParameters("/nonexistent/parameters.cfg"));
  // Unknown keys, comments, sections, ':' separators, CRLF and a repeated key (the last wins).
  auto p = parseHciParameters("[x]\r\n; c\r\nunknown = ???\r\nnum_cams_x: 4\r\nnum_cams_x = 5\r\n");
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_EQ(p->camerasX, 5);
}

TEST(HciParameters, GarbageNeverCrashes) {
  std::mt19937 generator(3);
  const std::string alphabet = "=:[]#;\n\r\t .-+e0123456789abcdefinx_";
  std::string valid = kAntinous;
  for (int trial = 0; trial < 2000; ++trial) {
    std::string text;
    if (trial % 2 == 0) {
      const int length = int(generator() % 300);
      for (int i = 0; i < length; ++i)
        text += char(trial % 4 == 0 ? generator() % 256 : alphabet[generator() % alphabet.size()]);
    } else {
      text = valid;  // the real file with a few bytes changed
      for (int i = 0; i < 3; ++i) text[generator() % text.size()] = char(generator() % 256);
    }
    auto p = parseHciParameters(text);
    if (p) {
      if (auto optics = hciOptics(*p)) {
        EXPECT_TRUE(optics->spatialStepMm > 0 && std::isfinite(*optics->focalLengthMm));
      }
    } else {
      EXPECT_FALSE(p.error().message.empty());
    }
  }
}

}  // namespace
}  // namespace lfcam
