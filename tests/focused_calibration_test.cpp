// The focused plenoptic calibration: Raytrix's XML and its JSON twin, the grid they place on an
// image, the lens types, and the refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "lfcam/focused/focused_calibration.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

// A calibration in Raytrix's layout (numbers of our own): hexagonal, three lens types.
std::string raytrixLikeXml(double offsetX = 12.5, double offsetY = -7.25, double rotation = 0.01) {
  return R"(<RayCalibData version="1.0">
  <offset units="pix"><x>)" +
         std::to_string(offsetX) + "</x><y>" + std::to_string(offsetY) + R"(</y></offset>
  <diameter units="pix">23.5</diameter>
  <rotation units="rad">)" +
         std::to_string(rotation) + R"(</rotation>
  <lens_border units="pix">1.5</lens_border>
  <tcp units="virtual_depth">2.5</tcp>
  <lens_base_x units="lens"><x>1</x><y>0</y></lens_base_x>
  <lens_base_y units="lens"><x>0.5</x><y>-0.866025388241</y></lens_base_y>
  <sub_grid_base units="lens"><x>3</x><y>-1.732050776482</y></sub_grid_base>
  <distortion type="radial"><function>constant</function><parameter count="0">0</parameter></distortion>
  <lens_type id="0"><offset units="lens"><x>0</x><y>0</y></offset>
    <depth_range units="virtual_depth"><min>1</min><max>3</max></depth_range></lens_type>
  <lens_type id="1"><offset units="lens"><x>1</x><y>0</y></offset>
    <depth_range units="virtual_depth"><min>2.8</min><max>4</max></depth_range></lens_type>
  <lens_type id="2"><offset units="lens"><x>-1</x><y>0</y></offset>
    <depth_range units="virtual_depth"><min>3.8</min><max>100</max></depth_range></lens_type>
</RayCalibData>
)";
}

TEST(FocusedCalibration, ReadsRaytrixXmlAsPlenopticToolboxPlacesIt) {
  const auto calibration = parseRayCalibXml(raytrixLikeXml(12.5, -7.25, 0), "c.xml", 640, 480);
  ASSERT_TRUE(calibration) << calibration.error().message;
  const LensletGrid& grid = calibration->grid;
  EXPECT_EQ(grid.packing, Packing::Hexagonal);
  EXPECT_DOUBLE_EQ(calibration->diameterPx(), 23.5);
  EXPECT_NEAR(grid.pitchY, 23.5 * std::sqrt(3.0) / 2, 1e-12);
  EXPECT_DOUBLE_EQ(calibration->borderPx, 1.5);
  EXPECT_DOUBLE_EQ(calibration->totalCoveringPlane.value_or(0), 2.5);
  ASSERT_EQ(calibration->lensTypes.size(), 3u);
  // The reference lens sits at the image's centre plus the offset, y up (pixel centres at
  // half-integers: PlenopticToolbox's (w - 1) / 2 with integer centres is the same point).
  const auto reference = grid.latticeCentre(calibration->referenceLens[0], calibration->referenceLens[1]);
  EXPECT_NEAR(reference[0], 320 + 12.5, 1e-9);
  EXPECT_NEAR(reference[1], 240 + 7.25, 1e-9);
  // Its right neighbour one diameter along x; the row below half a lens across.
  const auto right = grid.latticeCentre(calibration->referenceLens[0] + 1, calibration->referenceLens[1]);
  EXPECT_NEAR(right[0] - reference[0], 23.5, 1e-9);
  const auto below = grid.latticeCentre(calibration->referenceLens[0], calibration->referenceLens[1] + 1);
  EXPECT_NEAR(std::abs(below[0] - reference[0]), 11.75, 1e-9);
  EXPECT_NEAR(below[1] - reference[1], 23.5 * std::sqrt(3.0) / 2, 1e-9);
  // Every centre of the grid's first and last rows and columns, and no more, covers the image.
  int inside = 0;
  for (int j = 0; j < grid.rows; ++j)
    for (int i = 0; i < grid.columns; ++i) {
      const auto c = grid.latticeCentre(i, j);
      inside += c[0] >= 0 && c[0] < 640 && c[1] >= 0 && c[1] < 480;
    }
  EXPECT_GE(inside, grid.rows * (grid.columns - 1));
  EXPECT_EQ(grid.rows, int(std::floor((240 + 7.25) / grid.pitchY)) + int(std::floor((240 - 7.25) / grid.pitchY)) + 1);
}

TEST(FocusedCalibration, LensTypesLieAtTheReferenceLessTheirOffsets) {
  const auto calibration = parseRayCalibXml(raytrixLikeXml(), "c.xml", 640, 480);
  ASSERT_TRUE(calibration) << calibration.error().message;
  const auto [i0, j0] = calibration->referenceLens;
  EXPECT_EQ(calibration->lensType(i0, j0), 0);
  EXPECT_EQ(calibration->lensType(i0 - 1, j0), 1);  // offset (1, 0): at the reference less (1, 0)
  EXPECT_EQ(calibration->lensType(i0 + 1, j0), 2);  // offset (-1, 0)
  EXPECT_EQ(calibration->lensType(i0 + 3, j0), 0);
  // Every lens's six neighbours are of the two other types, three of each.
  const LensletGrid& grid = calibration->grid;
  std::map<int, int> counts;
  for (int j = 1; j + 1 < grid.rows; ++j)
    for (int i = 1; i + 1 < grid.columns; ++i) {
      const int type = calibration->lensType(i, j);
      ++counts[type];
      const auto centre = grid.latticeCentre(i, j);
      std::map<int, int> around;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          if (di == 0 && dj == 0) continue;
          const auto other = grid.latticeCentre(i + di, j + dj);
          if (std::hypot(other[0] - centre[0], other[1] - centre[1]) < 1.01 * grid.pitchX)
            ++around[calibration->lensType(i + di, j + dj)];
        }
      ASSERT_EQ(around[type], 0) << "lens " << i << "," << j;
      ASSERT_EQ(around[(type + 1) % 3], 3);
      ASSERT_EQ(around[(type + 2) % 3], 3);
    }
  EXPECT_EQ(counts.size(), 3u);
}

TEST(FocusedCalibration, XmlAndJsonRoundTrip) {
  test::TempDir dir;
  const auto original = parseRayCalibXml(raytrixLikeXml(-30.25, 14.5, -0.02), "c.xml", 500, 400);
  ASSERT_TRUE(original) << original.error().message;
  FocusedCalibration changed = original.value();
  changed.orientation = MicroImageOrientation::Inverted;
  changed.optics =
      FocusedOptics{.mainFocalLengthMm = 50, .mainLensToMicrolensesMm = 51.25, .microlensesToSensorMm = 0.4};
  for (const char* name : {"c.xml", "c.json"}) {
    ASSERT_TRUE(writeFocusedCalibration(dir.path() / name, changed));
    const auto back = readFocusedCalibration(dir.path() / name, 500, 400);
    ASSERT_TRUE(back) << back.error().message;
    EXPECT_EQ(back->orientation, MicroImageOrientation::Inverted) << name;
    EXPECT_EQ(back->grid.rows, changed.grid.rows);
    EXPECT_EQ(back->grid.columns, changed.grid.columns);
    EXPECT_NEAR(back->grid.rotationRad, changed.grid.rotationRad, 1e-11);
    for (int j = 0; j < changed.grid.rows; j += 3)
      for (int i = 0; i < changed.grid.columns; i += 2) {
        const auto a = changed.grid.latticeCentre(i, j), b = back->grid.latticeCentre(i, j);
        ASSERT_NEAR(a[0], b[0], 1e-8) << name;
        ASSERT_NEAR(a[1], b[1], 1e-8) << name;
        ASSERT_EQ(changed.lensType(i, j), back->lensType(i, j)) << name;
      }
    EXPECT_DOUBLE_EQ(back->lensTypes[2].maxVirtualDepth, 100) << name;
    ASSERT_TRUE(back->optics) << name;
    EXPECT_NEAR(back->optics->mainLensToMicrolensesMm, 51.25, 1e-9) << name;
    EXPECT_NEAR(back->optics->microlensesToSensorMm, 0.4, 1e-9) << name;
  }
}

TEST(FocusedCalibration, ASquareArrayWithOneLensType) {
  FocusedCalibration calibration = focusedGrid({101.5, 80.25}, 16, Packing::Square, 0, 200, 160);
  calibration.lensTypes = {LensType{}};
  test::TempDir dir;
  ASSERT_TRUE(writeFocusedCalibration(dir.path() / "s.xml", calibration));
  const auto back = readFocusedCalibration(dir.path() / "s.xml", 200, 160);
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(back->grid.packing, Packing::Square);
  EXPECT_EQ(back->lensType(3, 4), 0);
  EXPECT_EQ(back->grid.columns, 13);  // centres from 5.5 to 197.5
  EXPECT_EQ(back->grid.rows, 10);     // from 0.25 to 144.25
}

TEST(FocusedCalibration, RefusesWhatIsNotACalibrationOfThisImage) {
  auto refusal = [](const std::string& text, int width = 640, int height = 480) {
    const auto result = parseRayCalibXml(text, "bad.xml", width, height);
    return result ? std::string("accepted") : result.error().message;
  };
  auto replaced = [](std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  const std::string good = raytrixLikeXml();
  EXPECT_EQ(refusal("<html><body/></html>"), "bad.xml: not a Raytrix calibration (no <RayCalibData> element)");
  EXPECT_NE(refusal("<RayCalibData><offset>").find("bad.xml: not valid XML"), std::string::npos);
  EXPECT_EQ(refusal(replaced(good, "<diameter units=\"pix\">23.5</diameter>", "")), "bad.xml: diameter: missing");
  EXPECT_EQ(refusal(replaced(good, ">23.5<", ">wide<")), "bad.xml: diameter: expected a number, got \"wide\"");
  EXPECT_NE(refusal(replaced(good, "<x>0.5</x><y>-0.866025388241</y>", "<x>0.3</x><y>0.9</y>")).find("lens_base_y"),
            std::string::npos);
  EXPECT_NE(refusal(replaced(good, "<x>-1</x><y>0</y>", "<x>3</x><y>0</y>")).find("two lens types share lenses"),
            std::string::npos);
  EXPECT_NE(refusal(replaced(good, "<parameter count=\"0\">0</parameter>", "<parameter count=\"1\">0.01</parameter>"))
                .find("lens distortion is not supported"),
            std::string::npos);
  EXPECT_NE(refusal(raytrixLikeXml(900, 0)).find("outside the 640x480 image"), std::string::npos);
  // Microlenses nearer the main lens than its focal length: no real image falls on them.
  EXPECT_NE(refusal(replaced(good, "</RayCalibData>",
                             "<lfcam_optics><main_focal_length>50</main_focal_length><main_to_microlenses>40"
                             "</main_to_microlenses><microlenses_to_sensor>0.4</microlenses_to_sensor></lfcam_optics>"
                             "</RayCalibData>"))
                .find("lfcam_optics"),
            std::string::npos);
  EXPECT_NE(refusal(good, 60, 480).find("smaller than three micro-images"), std::string::npos);
  const auto json = parseFocusedCalibrationJson(R"({"offset": {"x": 0, "y": 0}, "diameter": 20, "lens_typez": []})",
                                                "bad.json", 640, 480);
  ASSERT_FALSE(json);
  EXPECT_EQ(json.error().message, "bad.json: lens_typez: unknown key");
  EXPECT_FALSE(parseFocusedCalibrationJson("{\"grid\": 1}", "g.json", 640, 480));
  const auto extension = readFocusedCalibration("calibration.txt", 640, 480);
  ASSERT_FALSE(extension);
  EXPECT_EQ(extension.error().code, ErrorCode::Usage);
}

}  // namespace
}  // namespace lfcam
