// Lenslet grid calibration: accuracy on simulator white and pinhole images against the true grid
// (gridFromCamera), robustness (mosaic, hot pixels, hint), grid.json, metadata hints, the median.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

#include <nlohmann/json.hpp>

#include "calibrate/calibrate_internal.hpp"
#include "calibrate/grid_json.hpp"
#include "lfcam/calibrate/calibrate.hpp"
#include "lfcam/simulate/scene.hpp"
#include "lfcam/simulate/simulate.hpp"
#include "simulate/camera_json.hpp"
#include "simulate/simulated_grid.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

constexpr double kDeg = M_PI / 180.0;

// A small prototype whose microlens images are `pitchPx` apart, matched f-numbers.
CameraModel testCamera(Packing packing, double pitchPx, double rotationDeg, std::array<double, 2> offsetPx,
                       ColorFilter filter) {
  CameraModel camera = CameraModel::paperPrototype(600, 600);
  MicrolensArray& m = *camera.microlenses;
  m.packing = packing;
  m.rotationDeg = rotationDeg;
  const double scale = 1.0 + m.separationMm() / camera.mainLens.imageDistanceMm();
  m.pitchMm = pitchPx * camera.sensor.pixelPitchMm / scale;
  m.offsetMm = {offsetPx[0] * camera.sensor.pixelPitchMm / scale, offsetPx[1] * camera.sensor.pixelPitchMm / scale};
  camera.mainLens.setImageSideFNumber(m.fNumber());
  camera.sensor.colorFilter = filter;
  camera.sensor.noise = true;
  return camera;
}

Image simulateWhite(const CameraModel& camera, int samplesPerPixel = 4) {
  auto scene = builtinScene("white", camera);
  EXPECT_TRUE(scene.ok());
  SimulationOptions options;
  options.samplesPerPixel = samplesPerPixel;
  return simulateCapture(*scene, camera, options).raw;
}

// Distance from `p` to the nearest centre of `grid`'s lattice (extended beyond its rectangle).
double distanceToLattice(const LensletGrid& grid, std::array<double, 2> p) {
  const double c = std::cos(grid.rotationRad), s = std::sin(grid.rotationRad);
  const double dx = p[0] - grid.origin[0], dy = p[1] - grid.origin[1];
  const double a = (c * dx + s * dy) / grid.pitchX, b = (-s * dx + c * dy) / grid.pitchY;
  double best = INFINITY;
  for (int j = int(std::round(b)) - 1; j <= int(std::round(b)) + 1; ++j)
    for (int i = int(std::round(a)) - 2; i <= int(std::round(a)) + 2; ++i) {
      const auto q = grid.centre(i, j);
      best = std::min(best, std::hypot(q[0] - p[0], q[1] - p[1]));
    }
  return best;
}

struct GridErrors {
  double centreRms = 0, rotationDeg = 0, pitchX = 0, pitchY = 0;
};

GridErrors compare(const LensletGrid& found, const LensletGrid& truth) {
  GridErrors e;
  double sum = 0;
  for (int j = 0; j < found.rows; ++j)
    for (int i = 0; i < found.columns; ++i) {
      const double d = distanceToLattice(truth, found.centre(i, j));
      sum += d * d;
    }
  e.centreRms = std::sqrt(sum / (found.rows * found.columns));
  e.rotationDeg = std::abs(found.rotationRad - truth.rotationRad) / kDeg;
  e.pitchX = std::abs(found.pitchX / truth.pitchX - 1);
  e.pitchY = std::abs(found.pitchY / truth.pitchY - 1);
  return e;
}

// The goals: centre RMS error 0.05 px, rotation 0.005 degrees, relative pitch 1e-4.
void expectAccurate(const LensletGrid& found, const LensletGrid& truth, const char* label) {
  constexpr double pitchTolerance = 1e-4;
  const GridErrors e = compare(found, truth);
  std::printf(
      "[%s] %s %dx%d (true %dx%d), pitch %.5f x %.5f px (true %.5f x %.5f), rotation %.5f deg; "
      "centre RMS error %.4f px, rotation error %.5f deg, pitch error %.2e / %.2e; fit: %d found, %d used, "
      "residual RMS %.4f px, max %.4f px\n",
      label, packingName(found.packing), found.columns, found.rows, truth.columns, truth.rows, found.pitchX,
      found.pitchY, truth.pitchX, truth.pitchY, found.rotationRad / kDeg, e.centreRms, e.rotationDeg, e.pitchX,
      e.pitchY, found.fit.lensletsFound, found.fit.lensletsUsed, found.fit.rmsResidualPx, found.fit.maxResidualPx);
  EXPECT_EQ(found.packing, truth.packing);
  EXPECT_LE(e.centreRms, 0.05);
  EXPECT_LE(e.rotationDeg, 0.005);
  EXPECT_LE(e.pitchX, pitchTolerance);
  EXPECT_LE(e.pitchY, pitchTolerance);
  EXPECT_NEAR(found.columns, truth.columns, 1);
  EXPECT_NEAR(found.rows, truth.rows, 1);
  EXPECT_GT(found.fit.lensletsUsed, 0.8 * found.fit.lensletsFound);
}

TEST(SimulatedGrid, MatchesTheSimulatorsCentres) {
  CameraModel camera = testCamera(Packing::Hexagonal, 13.37, 0.7, {3.2, -1.9}, ColorFilter::Mono);
  const LensletGrid grid = gridFromCamera(camera);
  const auto [columns, rows] = camera.microlensCounts();
  EXPECT_EQ(grid.columns, columns);
  EXPECT_EQ(grid.rows, rows);
  // The raw is the sensor turned by 180 degrees: the grid's microlens (i, j) is the simulator's
  // (columns - 1 - i, rows - 1 - j), for either parity of the row count.
  for (int extraRow : {0, 1}) {
    CameraModel other = camera;
    other.microlenses->rows = rows + extraRow;
    const LensletGrid g = gridFromCamera(other);
    EXPECT_EQ(g.hexParity, (rows + extraRow) & 1);
    for (int j : {0, 1, 2, g.rows - 1})
      for (int i : {0, 3, columns - 1}) {
        const auto a = g.centre(i, j), b = other.microlensImageCentrePx(columns - 1 - i, g.rows - 1 - j);
        EXPECT_NEAR(a[0], b[0], 1e-9) << i << ", " << j;
        EXPECT_NEAR(a[1], b[1], 1e-9) << i << ", " << j;
      }
  }
  EXPECT_NEAR(grid.pitchX, 13.37, 1e-9);
  EXPECT_NEAR(grid.pitchY, 13.37 * std::sqrt(3.0) / 2, 1e-9);
}

TEST(Calibrate, HexagonalBayerWhiteImage) {
  const CameraModel camera = testCamera(Packing::Hexagonal, 13.37, 0.8, {4.3, -2.7}, ColorFilter::RGGB);
  const Image white = simulateWhite(camera);
  CalibrationOptions options;
  options.colorFilter = ColorFilter::RGGB;
  options.blackLevel = camera.sensor.blackLevel;
  auto grid = calibrateGrid(white, options);
  ASSERT_TRUE(grid.ok()) << grid.error().message;
  expectAccurate(*grid, gridFromCamera(camera), "hexagonal RGGB");
}

TEST(Calibrate, SquareMonochromeWhiteImageRotatedOneDegree) {
  CameraModel camera = testCamera(Packing::Square, 13.37, -1.0, {-5.1, 2.2}, ColorFilter::Mono);
  camera.sensor.hotPixelFraction = 0.002;  // and dead ones below
  Image white = simulateWhite(camera);
  std::mt19937 random(7);
  for (int k = 0; k < 500; ++k) white.at(int(random() % 600), int(random() % 600), 0) = 0;
  auto grid = calibrateGrid(white, {});
  ASSERT_TRUE(grid.ok()) << grid.error().message;
  expectAccurate(*grid, gridFromCamera(camera), "square mono, hot and dead pixels");
}

// The fit on an even subset of the centres (what large grids use) against the fit on all of them.
TEST(Calibrate, SubsetFitAgreesWithTheFullFit) {
  const CameraModel camera = testCamera(Packing::Hexagonal, 13.37, 0.3, {2.1, 1.3}, ColorFilter::Mono);
  const Image white = simulateWhite(camera, 16);
  CalibrationOptions options;
  options.fitCentres = 0;
  auto all = calibrateGrid(white, options);
  options.fitCentres = 500;  // every second microlens each way
  auto subset = calibrateGrid(white, options);
  ASSERT_TRUE(all.ok() && subset.ok());
  EXPECT_LT(subset->fit.lensletsFound, all->fit.lensletsFound / 3);
  EXPECT_GT(subset->fit.lensletsFound, 100);
  EXPECT_EQ(subset->columns, all->columns);
  EXPECT_EQ(subset->rows, all->rows);
  EXPECT_EQ(subset->hexParity, all->hexParity);
  EXPECT_LT(compare(*subset, *all).centreRms, 0.02);
  expectAccurate(*subset, gridFromCamera(camera), "hexagonal, subset fit");
}

// Touching hexagonal discs, each with a brightness ramp about its own centre (an off-axis white
// image, brighter towards the optical axis): the centre of symmetry with each image's own lever
// stays where it is without the ramp, where a single ramp across the window (the neighbours' parts
// included) is pulled towards the bright side; that pull, growing with the distance from the
// axis, was the hexagonal white images' inward pitch bias of about 1e-4.
TEST(Calibrate, SymmetricCentreUnderPerImageRamps) {
  calibrate_detail::Lattice lattice;
  lattice.packing = Packing::Hexagonal;
  lattice.pitchX = 13.37;
  lattice.pitchY = 13.37 * std::sqrt(3.0) / 2;
  lattice.theta = 0.4 * kDeg;
  lattice.ox = 60.3;
  lattice.oy = 60.7;
  const auto render = [&](double gx, double gy) {  // ramp per pixel
    const double radius = 0.5 * 13.3;
    Image image(120, 120, 1);
    constexpr int kSub = 8;  // each pixel the mean over kSub x kSub points
    for (int y = 0; y < 120; ++y)
      for (int x = 0; x < 120; ++x) {
        double sum = 0;
        for (int sy = 0; sy < kSub; ++sy)
          for (int sx = 0; sx < kSub; ++sx) {
            const double px = x + (sx + 0.5) / kSub, py = y + (sy + 0.5) / kSub;
            for (int n = -2; n <= 2; ++n)
              for (int k = -2; k <= 2; ++k) {
                const auto c = lattice.centre(k, n);
                const double dx = px - c[0], dy = py - c[1];
                if (dx * dx + dy * dy <= radius * radius) sum += 1 + gx * dx + gy * dy;
              }
          }
        image.at(x, y, 0) = float(sum / (kSub * kSub));
      }
    return image;
  };
  const Image flat = render(0, 0), ramp = render(0.006, -0.003);
  const auto neighbours = lattice.neighbourOffsets();
  ASSERT_EQ(neighbours.size(), 6u);
  const auto centre = [&](const Image& image, bool perImage) {
    const auto e = calibrate_detail::refineSymmetric(image, 60.6, 60.4, 0.75 * 13.37, 10,
                                                     perImage ? neighbours : std::vector<std::array<double, 2>>{});
    EXPECT_TRUE(e.ok);
    return std::array<double, 2>{e.x, e.y};
  };
  const auto moved = [&](bool perImage) {
    const auto a = centre(flat, perImage), b = centre(ramp, perImage);
    return std::hypot(b[0] - a[0], b[1] - a[1]);
  };
  const double perImage = moved(true), oneRamp = moved(false);
  const auto still = centre(flat, true);
  std::printf(
      "[symmetric centre] error %.4f px without a ramp; the ramp moves it %.4f px with each image's lever, "
      "%.4f px with one ramp\n",
      std::hypot(still[0] - 60.3, still[1] - 60.7), perImage, oneRamp);
  EXPECT_LT(std::hypot(still[0] - 60.3, still[1] - 60.7), 0.05);  // bilinear samples of sharp edges
  EXPECT_LT(perImage, 0.01);
  EXPECT_LT(perImage, 0.2 * oneRamp);
}

TEST(Calibrate, PinholeSourceImage) {
  // The main lens stopped down to a pinhole (section 5.1): a sharp spot under each microlens.
  CameraModel camera = testCamera(Packing::Hexagonal, 13.37, 0.4, {1.5, 0.5}, ColorFilter::Mono);
  camera.mainLens.fNumber = 40;
  camera.sensor.exposure = 150;
  const Image pinhole = simulateWhite(camera);
  CalibrationOptions options;
  options.target = CalibrationTarget::Pinhole;
  auto grid = calibrateGrid(pinhole, options);
  ASSERT_TRUE(grid.ok()) << grid.error().message;
  expectAccurate(*grid, gridFromCamera(camera), "pinhole");
}

TEST(Calibrate, HintGivesTheSameGrid) {
  const CameraModel camera = testCamera(Packing::Square, 14.61, 0.3, {0, 0}, ColorFilter::Mono);
  const Image white = simulateWhite(camera);
  CalibrationOptions options;
  options.hint = LensletHint{14.5, 0.0, {0, 0}, Packing::Square};
  auto hinted = calibrateGrid(white, options);
  auto blind = calibrateGrid(white, {});
  ASSERT_TRUE(hinted.ok() && blind.ok());
  EXPECT_NEAR(hinted->pitchX, blind->pitchX, 1e-6);
  EXPECT_NEAR(hinted->origin[0], blind->origin[0], 0.01);
  EXPECT_EQ(hinted->columns, blind->columns);
  expectAccurate(*hinted, gridFromCamera(camera), "square with hint");
}

// A tiny image (about 12 x 13 microlenses) without a hint: found, or refused with a clear message.
// A sparse, dark scene by hand: discs of radius 5 on a rotated square lattice of pitch 12.3, lit
// only inside a vignetted circle (elsewhere at 1/500 under noise), each with a bright specimen spot
// off its centre, the same way over whole regions, then quantised to 8 bits like a JPEG frame.
TEST(Calibrate, SparseDarkSceneWithoutWhiteImage) {
  LensletGrid truth;
  truth.pitchX = truth.pitchY = 12.3;
  truth.rotationRad = 0.5 * kDeg;
  truth.origin = {7.1, 5.4};
  truth.columns = truth.rows = 34;
  const int size = 420;
  Image image(size, size, 1);
  std::mt19937 random(13);
  std::uniform_real_distribution<float> noise(-0.004f, 0.004f);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      double value = 0;
      for (int sy = 0; sy < 4; ++sy)
        for (int sx = 0; sx < 4; ++sx) {
          const double px = x + (sx + 0.5) / 4, py = y + (sy + 0.5) / 4;
          // The nearest microlens: the lattice coordinates rounded.
          const double c = std::cos(truth.rotationRad), s = std::sin(truth.rotationRad);
          const double dx = px - truth.origin[0], dy = py - truth.origin[1];
          const auto o = truth.centre(int(std::lround((c * dx + s * dy) / truth.pitchX)),
                                      int(std::lround((-s * dx + c * dy) / truth.pitchY)));
          const double r = std::hypot(px - o[0], py - o[1]);
          if (r > 5) continue;
          const double fromAxis = std::hypot(o[0] - 230, o[1] - 190) / 150;
          const double lit = fromAxis < 1 ? std::pow(std::cos(0.5 * M_PI * fromAxis), 2) : 0.002;
          // The specimen: a spot 2.5 px off centre, towards +x left of x = 210, towards +y right of it.
          const double ox = o[0] < 210 ? 2.5 : 0, oy = o[0] < 210 ? 0 : 2.5;
          const double spot = 3 * std::exp(-(std::pow(px - o[0] - ox, 2) + std::pow(py - o[1] - oy, 2)) / 2);
          value += lit * (0.3 + spot) / 16;
        }
      image.at(x, y, 0) = std::round(255 * std::clamp(float(value) + noise(random), 0.0f, 1.0f)) / 255;
    }
  CalibrationOptions options;
  options.target = CalibrationTarget::Scene;
  auto found = calibrateGridDetailed(image, options, "sparse.png");
  ASSERT_TRUE(found.ok()) << found.error().message;
  const LensletGrid& grid = found->grid;
  const GridErrors e = compare(grid, truth);
  std::printf("sparse scene: pitch %.4f x %.4f, fit %d found, %d used, RMS %.4f px; centres off by %.4f px RMS\n",
              grid.pitchX, grid.pitchY, grid.fit.lensletsFound, grid.fit.lensletsUsed, grid.fit.rmsResidualPx,
              e.centreRms);
  EXPECT_TRUE(grid.fit.selfCalibrated);
  EXPECT_LT(e.pitchX, 1e-3);
  EXPECT_LT(e.pitchY, 1e-3);
  EXPECT_LT(e.centreRms, 0.15);
  EXPECT_LT(grid.fit.rmsResidualPx, 0.15);
  // The dark microlenses are left out of the fit; the grid still spans the lit circle.
  EXPECT_LT(grid.fit.lensletsFound, grid.columns * grid.rows / 2);
  EXPECT_GE(grid.columns, 24);
}

TEST(Calibrate, TinyHexagonalImageWithoutHint) {
  CameraModel camera = testCamera(Packing::Hexagonal, 13.37, 0.5, {1.1, -0.7}, ColorFilter::Mono);
  camera.sensor.width = camera.sensor.height = 160;
  const Image white = simulateWhite(camera);
  auto grid = calibrateGrid(white, {});
  ASSERT_TRUE(grid.ok()) << grid.error().message;
  const GridErrors e = compare(*grid, gridFromCamera(camera));
  std::printf("[tiny hex] %dx%d, centre RMS error %.4f px, pitch error %.2e\n", grid->columns, grid->rows, e.centreRms,
              e.pitchX);
  EXPECT_EQ(grid->packing, Packing::Hexagonal);
  EXPECT_LE(e.centreRms, 0.1);
  EXPECT_LE(e.pitchX, 2e-3);
}

TEST(Calibrate, RefusesImagesWithoutALattice) {
  Image flat(200, 200, 1);
  for (float& v : flat.pixels()) v = 0.5f;
  auto grid = calibrateGrid(flat, {});
  ASSERT_FALSE(grid.ok());
  EXPECT_EQ(grid.error().code, ErrorCode::Format);
  EXPECT_NE(grid.error().message.find("image"), std::string::npos);
  EXPECT_FALSE(calibrateGrid(Image(), {}).ok());
  CalibrationOptions options;
  options.hint = LensletHint{0.5, 0, {0, 0}, Packing::Square};
  auto bad = calibrateGrid(flat, options);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().code, ErrorCode::Usage);
}

TEST(LensletGridJson, RoundTripsAndRejectsBadFiles) {
  LensletGrid grid;
  grid.packing = Packing::Hexagonal;
  grid.pitchX = 14.29;
  grid.pitchY = 12.38;
  grid.rotationRad = 0.001;
  grid.origin = {7.5, 8.25};
  grid.columns = 540;
  grid.rows = 433;
  grid.hexParity = 1;
  grid.fit = {1000, 990, 0.02, 0.1};
  const test::TempDir dir;
  const auto path = dir.path() / "grid.json";
  ASSERT_TRUE(writeGrid(path, grid).ok());
  auto back = readGrid(path);
  ASSERT_TRUE(back.ok()) << back.error().message;
  EXPECT_EQ(back->packing, grid.packing);
  EXPECT_DOUBLE_EQ(back->pitchX, grid.pitchX);
  EXPECT_NEAR(back->rotationRad, grid.rotationRad, 1e-15);
  EXPECT_EQ(back->hexParity, 1);
  EXPECT_EQ(back->fit.lensletsUsed, 990);
  for (int j : {0, 1}) EXPECT_NEAR(back->centre(3, j)[0], grid.centre(3, j)[0], 1e-9);
  // Row 0 is shifted when hexParity is 1.
  EXPECT_NEAR(grid.centre(0, 0)[0] - grid.origin[0], 0.5 * 14.29 * std::cos(0.001), 1e-9);

  nlohmann::json json = gridToJson(grid);
  json["pitch_x_px"] = -1;
  auto bad = gridFromJson(json, "g.json");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("g.json: pitch_x_px"), std::string::npos);
  json = gridToJson(grid);
  json.erase("rows");
  EXPECT_FALSE(gridFromJson(json, "g.json").ok());
  json = gridToJson(grid);
  json["extra"] = 1;
  EXPECT_FALSE(gridFromJson(json, "g.json").ok());
  EXPECT_EQ(readGrid(dir.path() / "missing.json").error().code, ErrorCode::Io);
}

TEST(GridWarp, InterpolatesRoundTripsAndIsFittedFromCentres) {
  LensletGrid grid;
  grid.pitchX = grid.pitchY = 20;
  grid.origin = {10, 10};
  grid.columns = 65;
  grid.rows = 49;
  // A known smooth field: control points every 16 microlenses, 5 x 4 of them.
  auto field = [](double i, double j) {
    return std::array<double, 2>{0.8 * std::sin(i / 20.0) * std::cos(j / 25.0), 0.5 * std::cos(i / 30.0 + j / 15.0)};
  };
  std::vector<DetectedCentre> centres;
  std::mt19937 random(53);
  std::normal_distribution<double> noise(0, 0.05);
  for (int j = 0; j < grid.rows; ++j)
    for (int i = 0; i < grid.columns; ++i) {
      if (i > 50 && j > 30) continue;  // a corner without signal: the warp carries on across it
      const auto p = grid.centre(i, j);
      const auto d = field(i, j);
      centres.push_back({i, j, p[0] + d[0] + noise(random), p[1] + d[1] + noise(random), 0, true});
    }
  calibrate_detail::fitGridWarp(grid, centres);
  EXPECT_EQ(grid.warp.columns, 5);
  EXPECT_EQ(grid.warp.rows, 4);
  // The field is smooth on the mesh's scale: what is left is the noise and the bilinear error.
  EXPECT_LT(grid.fit.rmsResidualPx, 0.1);
  std::printf("warp fitted to a known field: residual RMS %.4f px (noise 0.0707)\n", grid.fit.rmsResidualPx);
  // centre() adds the bilinear offset; latticeCentre() does not; the control points sit on
  // microlenses 0, 16, 32, ...
  const auto& corner = grid.warp.offsets[0];
  EXPECT_NEAR(grid.centre(0, 0)[0] - grid.latticeCentre(0, 0)[0], corner[0], 1e-12);
  const auto mid = grid.centre(8, 0), a = grid.warp.offsets[0], b = grid.warp.offsets[1];
  EXPECT_NEAR(mid[1] - grid.latticeCentre(8, 0)[1], 0.5 * (a[1] + b[1]), 1e-12);

  const test::TempDir dir;
  ASSERT_TRUE(writeGrid(dir.path() / "grid.json", grid).ok());
  auto back = readGrid(dir.path() / "grid.json");
  ASSERT_TRUE(back.ok()) << back.error().message;
  for (int j : {0, 17, 48})
    for (int i : {0, 9, 64}) {
      EXPECT_NEAR(back->centre(i, j)[0], grid.centre(i, j)[0], 1e-9);
      EXPECT_NEAR(back->centre(i, j)[1], grid.centre(i, j)[1], 1e-9);
    }
  nlohmann::json json = gridToJson(grid);
  json["warp"]["offsets_px"].erase(0);
  const auto bad = gridFromJson(json, "g.json");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("warp.offsets_px"), std::string::npos) << bad.error().message;
}

TEST(LensletHint, FromCameraJsonAndLytroMetadata) {
  const CameraModel camera = testCamera(Packing::Hexagonal, 13.37, 0.5, {0, 0}, ColorFilter::Mono);
  auto hint = lensletHintFromJson(cameraToJson(camera), "camera.json");
  ASSERT_TRUE(hint.ok()) << hint.error().message;
  EXPECT_NEAR(hint->pitchPx, 13.37, 1e-9);
  EXPECT_NEAR(hint->rotationRad, 0.5 * kDeg, 1e-12);
  EXPECT_EQ(hint->packing, Packing::Hexagonal);
  const nlohmann::json lytro = {{"devices",
                                 {{"sensor", {{"pixelPitch", 1.4e-6}}},
                                  {"mla",
                                   {{"tiling", "hexUniformRowMajor"},
                                    {"lensPitch", 1.4e-5},
                                    {"rotation", 0.002},
                                    {"sensorOffset", {{"x", 2.8e-6}, {"y", -1.4e-6}, {"z", 2.5e-5}}}}}}}};
  auto fromLytro = lensletHintFromJson({{"frame", {{"metadata", lytro}}}}, "frame.json");
  ASSERT_TRUE(fromLytro.ok()) << fromLytro.error().message;
  EXPECT_NEAR(fromLytro->pitchPx, 10.0, 1e-9);
  EXPECT_NEAR(fromLytro->rotationRad, 0.002, 1e-12);
  EXPECT_NEAR(fromLytro->offsetPx[0], 2.0, 1e-9);
  EXPECT_EQ(fromLytro->packing, Packing::Hexagonal);
  EXPECT_FALSE(lensletHintFromJson({{"a", 1}}, "x.json").ok());
}

TEST(Median3x3, FastKernelMatchesReference) {
  std::mt19937 random(3);
  std::uniform_real_distribution<float> value(0, 1);
  for (auto [w, h] : {std::pair{1, 1}, {2, 5}, {3, 3}, {17, 9}, {64, 31}}) {
    Image image(w, h, 1);
    for (float& v : image.pixels()) v = value(random);
    const Image fast = median3x3(image), slow = calibrate_detail::median3x3Reference(image);
    for (std::size_t k = 0; k < fast.pixels().size(); ++k)
      ASSERT_EQ(fast.pixels()[k], slow.pixels()[k]) << w << "x" << h;
  }
}

// The streamed preparation (every step per band of rows) against the whole-image reference:
// the same floats, for every combination of steps, sizes down to one pixel, and regions.
TEST(CalibratePrepare, FastPathMatchesReference) {
  std::mt19937 random(5);
  std::uniform_real_distribution<float> value(0, 1);
  struct Case {
    ColorFilter filter;
    CalibrationTarget target;
    int channels;
  };
  for (const Case& c :
       {Case{ColorFilter::Mono, CalibrationTarget::White, 1}, Case{ColorFilter::GRBG, CalibrationTarget::White, 1},
        Case{ColorFilter::RGGB, CalibrationTarget::Pinhole, 1}, Case{ColorFilter::Mono, CalibrationTarget::Pinhole, 2},
        Case{ColorFilter::BGGR, CalibrationTarget::Scene, 3}})
    for (auto [w, h] : {std::pair{1, 1}, {2, 5}, {3, 3}, {37, 29}, {64, 300}}) {
      Image image(w, h, c.channels);
      for (float& v : image.pixels()) v = value(random);
      CalibrationOptions options;
      options.colorFilter = c.filter;
      options.target = c.target;
      options.blackLevel = 0.05;
      const calibrate_detail::PhaseGains gains = calibrate_detail::phaseGains(image, options);
      for (bool smoothed : {false, true}) {
        const Image slow = calibrate_detail::prepareReference(image, options, smoothed);
        const Image fast = calibrate_detail::prepareRegion(image, options, gains, 0, 0, w, h, smoothed);
        for (std::size_t k = 0; k < fast.pixels().size(); ++k)
          ASSERT_EQ(fast.pixels()[k], slow.pixels()[k]) << w << "x" << h << " smoothed " << smoothed << " at " << k;
        // A region is that part of the whole.
        const int x0 = w / 3, y0 = h / 4, x1 = std::max(x0 + 1, w - w / 5), y1 = std::max(y0 + 1, h - h / 3);
        const Image part = calibrate_detail::prepareRegion(image, options, gains, x0, y0, x1, y1, smoothed);
        for (int y = y0; y < y1; ++y)
          for (int x = x0; x < x1; ++x)
            ASSERT_EQ(part.at(x - x0, y - y0, 0), slow.at(x, y, 0)) << w << "x" << h << " at " << x << "," << y;
      }
    }
}

// The centroid over the disc's span with the square root on its rim only, against the whole
// window through the weight's formula, on random images, radii and start points: the same floats.
TEST(Calibrate, CentroidFastPathMatchesReference) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> value(0, 1);
  std::uniform_real_distribution<double> position(12, 48), radius(0.4, 9);
  Image image(60, 60, 1);
  for (float& v : image.pixels()) v = value(random);
  int converged = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const double x = position(random), y = position(random), r = radius(random);
    const auto fast = calibrate_detail::refineCentre(image, x, y, r, 20, 1.5, 0.01);
    const auto slow = calibrate_detail::refineCentreReference(image, x, y, r, 20, 1.5, 0.01);
    ASSERT_EQ(fast.ok, slow.ok) << trial;
    ASSERT_EQ(fast.x, slow.x) << trial;
    ASSERT_EQ(fast.y, slow.y) << trial;
    ASSERT_EQ(fast.contrast, slow.contrast) << trial;
    converged += fast.ok;
  }
  EXPECT_GT(converged, 10);
}

// The symmetric centre resampled once per step against every sample interpolated on its own, on
// random images (smoothed noise) and start points: the same centres.
TEST(Calibrate, SymmetricCentreFastPathMatchesReference) {
  std::mt19937 random(11);
  std::uniform_real_distribution<float> value(0, 1);
  std::uniform_real_distribution<double> position(15, 45);
  Image noise(60, 60, 1);
  for (float& v : noise.pixels()) v = value(random);
  const Image image = calibrate_detail::smoothBinomial(calibrate_detail::smoothBinomial(noise));
  calibrate_detail::Lattice lattice;
  lattice.packing = Packing::Hexagonal;
  lattice.pitchX = 9.3;
  lattice.pitchY = 9.3 * std::sqrt(3.0) / 2;
  int converged = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const double x = position(random), y = position(random), radius = trial % 2 ? 6.5 : 4.2;
    const auto neighbours = trial % 3 ? lattice.neighbourOffsets() : std::vector<std::array<double, 2>>{};
    const auto fast = calibrate_detail::refineSymmetric(image, x, y, radius, 6, neighbours);
    const auto slow = calibrate_detail::refineSymmetricReference(image, x, y, radius, 6, neighbours);
    ASSERT_EQ(fast.ok, slow.ok) << trial;
    converged += fast.ok;
    if (!fast.ok) continue;
    EXPECT_NEAR(fast.x, slow.x, 1e-6) << trial;
    EXPECT_NEAR(fast.y, slow.y, 1e-6) << trial;
  }
  EXPECT_GT(converged, 10);
}

}  // namespace
}  // namespace lfcam
