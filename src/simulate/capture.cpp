// Ground truth (ideal light field, depth) and the output folder of `lfcam simulate`.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <numeric>
#include <random>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/memory_budget.hpp"
#include "core/parallel.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "lfcam/simulate/simulate.hpp"

#include "lfcam/focused/focused_calibration.hpp"
#include "lfcam/focused/photo_frame.hpp"
#include "lfcam/simulate/focused_truth.hpp"
#include "simulate/camera_json.hpp"
#include "simulate/tracing.hpp"

namespace lfcam {

using simulate_detail::Hit;
using simulate_detail::PreparedScene;

namespace {

struct ViewGrid {
  int views = 1;
  double stepMm = 0;  // du on the lens
};

ViewGrid viewGrid(const CameraModel& camera) {
  ViewGrid grid;
  grid.stepMm = camera.mainLens.imageDistanceMm() * camera.sensor.pixelPitchMm / camera.microlenses->separationMm();
  grid.views = std::max(1, int(std::lround(camera.microlensImageDiameterPx())));
  return grid;
}

}  // namespace

Result<LightField> idealLightField(const Scene& scene, const CameraModel& camera) {
  return idealLightFieldBoxFiltered(scene, camera, 1);
}

Result<LightField> idealLightFieldBoxFiltered(const Scene& scene, const CameraModel& camera, int boxSamples) {
  if (!camera.microlenses) return makeError(ErrorCode::Usage, "ideal light field: the camera has no microlens array");
  const int box = std::clamp(boxSamples, 1, 16);
  const auto counts = camera.microlensCounts();  // named, not bound: lambdas capture them (clang)
  const int columns = counts[0], rows = counts[1];
  const ViewGrid grid = viewGrid(camera);
  const int channels = camera.sensor.colorFilter == ColorFilter::Mono ? 1 : 3;
  // Samples and weight, float each.
  LFCAM_TRY(checkMemory("ideal light field",
                        checkedProduct({std::uint64_t(grid.views), std::uint64_t(grid.views), std::uint64_t(columns),
                                        std::uint64_t(rows), std::uint64_t(channels + 1), sizeof(float)}),
                        std::to_string(grid.views) + " x " + std::to_string(grid.views) + " views of " +
                            std::to_string(columns) + " x " + std::to_string(rows) + " samples"));
  LightField lf(LightFieldShape{grid.views, grid.views, columns, rows, channels});
  lf.enableWeight(0);
  const PreparedScene prepared(scene, camera);
  const double radius = 0.5 * camera.mainLens.apertureDiameterMm();
  // Box filter: lens offsets (fractions of a view step) paired with microlens-cell offsets (mm,
  // in the array's turned frame), box x box strata each, paired by a fixed shuffle.
  const MicrolensArray& array = *camera.microlenses;
  const bool hex = array.packing == Packing::Hexagonal;
  const double shrink = std::sqrt(array.fillFactor);
  const double halfA = 0.5 * array.pitchMm * shrink,
               halfB = (hex ? array.pitchMm / std::sqrt(3.0) : 0.5 * array.pitchMm) * shrink;
  const double cosR = std::cos(array.rotationDeg * M_PI / 180), sinR = std::sin(array.rotationDeg * M_PI / 180);
  struct BoxPoint {
    double lensX, lensY, cellX, cellY;
  };
  std::vector<BoxPoint> points;
  const int count = box * box;
  std::vector<int> pairing(static_cast<std::size_t>(count));
  std::iota(pairing.begin(), pairing.end(), 0);
  std::mt19937 shuffle(12345);  // fixed: the same field every run
  for (int k = count - 1; k > 0; --k) std::swap(pairing[std::size_t(k)], pairing[shuffle() % unsigned(k + 1)]);
  for (int k = 0; k < count; ++k) {
    const int m = pairing[std::size_t(k)];
    const double fx = ((k % box) + 0.5) / box - 0.5, fy = ((k / box) + 0.5) / box - 0.5;
    const double a = box == 1 ? 0 : (2 * (((m % box) + 0.5) / box) - 1) * halfA;
    const double b = box == 1 ? 0 : (2 * (((m / box) + 0.5) / box) - 1) * halfB;
    if (hex && std::abs(a) * 0.5 + std::abs(b) * 0.8660254037844386 > 0.5 * array.pitchMm * shrink) continue;
    points.push_back({box == 1 ? 0 : fx, box == 1 ? 0 : fy, cosR * a - sinR * b, sinR * a + cosR * b});
  }
  parallelFor(0, std::size_t(grid.views) * grid.views, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t view = begin; view < end; ++view) {
      const int u = int(view % grid.views), v = int(view / grid.views);
      const double lensX = lf.uFromCentre(u) * grid.stepMm, lensY = lf.vFromCentre(v) * grid.stepMm;
      const float inside = lensX * lensX + lensY * lensY <= radius * radius ? 1.0f : 0.0f;
      float* weight = lf.weightPlane(u, v);
      for (int j = 0; j < rows; ++j) {
        for (int i = 0; i < columns; ++i) {
          const auto centre = camera.microlensCentreMm(i, j);
          Rgb sum{0, 0, 0};
          int hits = 0;
          for (const BoxPoint& p : points) {
            // A ray through the cell point d off the microlens's centre meets the lens d further
            // on (the microlens images the lens onto the sensor).
            const double x = lensX + p.lensX * grid.stepMm + p.cellX, y = lensY + p.lensY * grid.stepMm + p.cellY;
            if (points.size() > 1 && x * x + y * y > radius * radius) continue;  // stopped by the aperture
            const Hit hit = prepared.traceThroughLens(x, y, centre[0] + p.cellX, centre[1] + p.cellY);
            for (int c = 0; c < 3; ++c) sum[c] += hit.radiance[c];
            ++hits;
          }
          if (hits == 0) {  // the whole footprint outside the aperture: the centre ray, as unfiltered
            const Hit hit = prepared.traceThroughLens(lensX, lensY, centre[0], centre[1]);
            sum = hit.radiance;
            hits = 1;
          }
          for (int c = 0; c < 3; ++c) sum[c] /= float(hits);
          const int s = columns - 1 - i, t = rows - 1 - j;  // turned the right way up
          if (channels == 1)
            lf.at(u, v, s, t, 0) = 0.2126f * sum[0] + 0.7152f * sum[1] + 0.0722f * sum[2];
          else
            for (int c = 0; c < 3; ++c) lf.at(u, v, s, t, c) = sum[c];
          weight[std::size_t(t) * columns + s] = inside;
        }
      }
    }
  });
  Optics optics;
  optics.lensStepMm = grid.stepMm;
  optics.spatialStepMm = camera.microlenses->pitchMm;
  optics.lensToMicrolensMm = camera.mainLens.imageDistanceMm();
  optics.focalLengthMm = camera.mainLens.focalLengthMm;
  lf.metadata.optics = optics;
  lf.metadata.source = "lfcam simulate: ideal light field of scene \"" + scene.name + "\"";
  return lf;
}

namespace {

// Depth of the rays from the lens point (lensX, lensY) mm through each microlens centre.
Result<Image> depthFromLensPoint(const Scene& scene, const CameraModel& camera, double lensX, double lensY) {
  if (!camera.microlenses) return makeError(ErrorCode::Usage, "ideal depth: the camera has no microlens array");
  const auto counts = camera.microlensCounts();
  const int columns = counts[0], rows = counts[1];
  Image depth(columns, rows, 1);
  const PreparedScene prepared(scene, camera);
  parallelFor(0, std::size_t(rows), 4, [&](std::size_t begin, std::size_t end) {
    for (std::size_t j = begin; j < end; ++j)
      for (int i = 0; i < columns; ++i) {
        const auto centre = camera.microlensCentreMm(i, int(j));
        depth.at(columns - 1 - i, rows - 1 - int(j), 0) =
            float(prepared.traceThroughLens(lensX, lensY, centre[0], centre[1]).depth);
      }
  });
  return depth;
}

}  // namespace

Result<Image> idealDepth(const Scene& scene, const CameraModel& camera) {
  return depthFromLensPoint(scene, camera, 0, 0);
}

Result<Image> idealDepthOfView(const Scene& scene, const CameraModel& camera, int u, int v) {
  if (!camera.microlenses) return makeError(ErrorCode::Usage, "ideal depth: the camera has no microlens array");
  const ViewGrid grid = viewGrid(camera);
  if (u < 0 || v < 0 || u >= grid.views || v >= grid.views)
    return makeError(ErrorCode::Usage, "ideal depth: view (" + std::to_string(u) + ", " + std::to_string(v) +
                                           ") is outside the " + std::to_string(grid.views) + " x " +
                                           std::to_string(grid.views) + " views");
  const double centre = 0.5 * (grid.views - 1);
  return depthFromLensPoint(scene, camera, (u - centre) * grid.stepMm, (v - centre) * grid.stepMm);
}

namespace {

Status writeRaw(const std::filesystem::path& path, const Image& raw, const std::string& what) {
  Image codes(raw.width(), raw.height(), 1);
  for (std::size_t k = 0; k < raw.pixels().size(); ++k) codes.pixels()[k] = raw.pixels()[k] / 65535.0f;
  ImageWriteOptions options;
  options.sampleType = SampleType::UInt16;
  options.description = "lfcam simulate: " + what + "; 16-bit codes are the sensor's digital numbers (see camera.json)";
  return writeImage(path, codes, options);
}

Status writeText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out) return makeError(ErrorCode::Io, path.string() + ": cannot write");
  return {};
}

}  // namespace

Status writeSimulation(const std::filesystem::path& folder, const Scene& scene, const CameraModel& camera,
                       const SimulationOptions& options, const CaptureOutputs& outputs,
                       const ProgressCallback& progress) {
  LFCAM_TRY(camera.validate(folder.string()));
  if (outputs.rawExtension != ".png" && outputs.rawExtension != ".tiff" && outputs.rawExtension != ".tif")
    return makeError(ErrorCode::Usage, "raw extension must be .png or .tiff, not " + outputs.rawExtension);
  const double shares = outputs.white ? 0.45 : 0.9;
  auto report = [&](double from, double span) {
    return [&progress, from, span](double f) {
      if (progress) progress(from + span * f);
    };
  };
  return writeFolderAtomically(folder, [&](const std::filesystem::path& temporary) -> Status {
    const SensorCapture capture = simulateCapture(scene, camera, options, report(0, shares));
    LFCAM_TRY(writeRaw(temporary / ("raw" + outputs.rawExtension), capture.raw,
                       "raw sensor image of scene \"" + scene.name + "\""));
    if (outputs.white) {
      LFCAM_ASSIGN_OR_RETURN(auto white, builtinScene("white", camera));
      const SensorCapture whiteCapture = simulateCapture(white, camera, options, report(shares, shares));
      LFCAM_TRY(writeRaw(temporary / ("white" + outputs.rawExtension), whiteCapture.raw, "white image"));
    }
    nlohmann::json json = cameraToJson(camera);
    json["scene"] = scene.name;
    json["samples_per_pixel"] = options.samplesPerPixel;
    json["rays_traced"] = capture.rays;
    if (camera.focusedPlenoptic()) {
      LFCAM_ASSIGN_OR_RETURN(const FocusedCalibration calibration, focusedCalibrationFromCamera(camera));
      const double pixelsPerLens = defaultPixelsPerLens(calibration);
      LFCAM_TRY(writeFocusedCalibration(temporary / "raw.xml", calibration));
      json["focused"] = {{"calibration", "raw.xml"},
                         {"pixels_per_lens", pixelsPerLens},
                         {"ideal", "ideal.pfm: the all-in-focus photograph on that frame (linear RGB)"},
                         {"virtual_depth", "virtual_depth.pfm: the virtual depth of each of its pixels"}};
      if (outputs.groundTruth) {
        LFCAM_ASSIGN_OR_RETURN(auto truth, focusedTruth(scene, camera, focusedPhotoFrame(calibration, pixelsPerLens)));
        LFCAM_TRY(writeImage(temporary / "ideal.pfm", truth.allInFocus));
        LFCAM_TRY(writeImage(temporary / "virtual_depth.pfm", truth.virtualDepth));
      }
    } else if (camera.microlenses) {
      const ViewGrid grid = viewGrid(camera);
      json["light_field"] = {
          {"file", "ideal.lf.h5"},
          {"views", grid.views},
          {"lens_step_mm", grid.stepMm},
          {"spatial_step_mm", camera.microlenses->pitchMm},
          {"orientation",
           "raw and white as a camera stores them (the sensor turned 180 degrees, the scene upright); "
           "(s, t) of ideal.lf.h5 and depth.pfm is microlens (i, j) = (s, t) of lattice_px"},
          {"depth", "depth.pfm: mm along z to the surface seen by the central ray through each microlens; inf: none"}};
    }
    LFCAM_TRY(writeText(temporary / "camera.json", json.dump(2) + "\n"));
    if (outputs.groundTruth && camera.microlenses && !camera.focusedPlenoptic()) {
      LFCAM_ASSIGN_OR_RETURN(auto depth, idealDepth(scene, camera));
      LFCAM_TRY(writeImage(temporary / "depth.pfm", depth));
      LFCAM_ASSIGN_OR_RETURN(auto lf, idealLightField(scene, camera));
      LFCAM_TRY(writeLightField(temporary / "ideal.lf.h5", lf));
    }
    if (progress) progress(1.0);
    return {};
  });
}

}  // namespace lfcam
