// Shared by the experiments: the capture chain (scene -> raw -> light field), the conventional
// camera, cameras and targets of section 6, best-focus search, and the report writer.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/experiments/experiments.hpp"
#include "lfcam/simulate/camera_model.hpp"
#include "lfcam/simulate/scene.hpp"

namespace lfcam::experiments {

// ---- captures ---------------------------------------------------------------------------------

// A scene traced once through a camera: the noise-free irradiance of the scene and of a white
// field (for the decoder's white image and the conventional photo's flat field). Frames made from
// it differ only in sensor noise, as repeated exposures of a still scene do.
struct TracedCapture {
  CameraModel camera;
  Image irradiance;       // per unit scene radiance, as SensorCapture::irradiance
  Image whiteIrradiance;  // of a white (radiance 1) field
};
// `traces` traces with different sample positions are averaged: a small light seen through a
// wide aperture is hit by few of a pixel's rays (Monte Carlo noise).
Result<TracedCapture> traceCapture(const Scene& scene, const CameraModel& camera, int samplesPerPixel, int traces = 1);

// The one place where a light-field camera's exposure becomes a light field: the raw frame
// (sensor model with `seed`, or noise-free) decoded into L(u, v, s, t) in scene radiance units,
// with weights from the white image. The camera must have a microlens array.
Result<LightField> captureLightField(const TracedCapture& traced, bool noise, std::uint64_t seed);

// A conventional photograph from a camera without microlenses, in scene radiance units (divided
// by the white field), upright like the light field's views (the raw is stored as a camera reads it out).
Result<Image> conventionalPhoto(const TracedCapture& traced, bool noise, std::uint64_t seed);

// ---- cameras and targets ----------------------------------------------------------------------

// The paper's prototype with `microlenses` x `microlenses` microlenses and exactly
// `pixelsPerMicrolens` pixels under each microlens image (pixel pitch chosen so), monochrome,
// main lens at image-side f/4 to match the microlenses, focused at `focusMm` (18 inches).
CameraModel plenopticCamera(int microlenses, int pixelsPerMicrolens, double focusMm = 457.2);
// The same main lens stopped to image-side `fNumber`, no microlenses: one pixel per microlens of
// `plenoptic` (the paper's "adding up all light under each microlens"), with the light gathering
// of the pixels it replaces (electrons, full well and summed read noise scaled by their area),
// digitised with 16 bits.
CameraModel conventionalCamera(const CameraModel& plenoptic, double fNumber);

// The distance at which a point's image on the microlens plane is a blur disc `blurMicrolenses`
// microlenses across through the image-side f/4 aperture: the target "moved slightly closer".
double defocusedDistanceMm(const CameraModel& plenoptic, double blurMicrolenses);
// A pinhole (small disc light on black) at `distanceMm` whose sharp image is one microlens across.
Scene pinholeScene(const CameraModel& plenoptic, double distanceMm);
// The resolution chart filling the field at `distanceMm`.
Scene chartScene(const CameraModel& plenoptic, double distanceMm);

// A white field (radiance 1 everywhere): the white image's scene.
Scene whiteScene();
// `photo` (channel 0) divided by `peak` (0: by its brightest pixel) and enlarged `scale` times
// (nearest), so that pixels stay visible in a report.
Image forDisplay(const Image& photo, int scale, double peak = 0);

// ---- refocusing -------------------------------------------------------------------------------

struct BestFocus {
  // Shift-and-add of the views (no supersampling, no blending of views): lfcam's photograph.
  double slope = 0;
  double cutoff = 0;  // cycles per pixel, 75% energy
  Image photo;
  // The quadrature method of section 5.2 (aperture supersampled, views blended quadrilinearly):
  // the paper's refocusing, kept to show what its filter costs.
  double quadratureSlope = 0, quadratureCutoff = 0;
  Image quadraturePhoto;
};
// Finds the focus over the light field's whole refocus range (quadrature method, coarse to fine)
// by how tightly the point's light is gathered, then within +-0.5 pixel per view step of it the
// slope of highest 75%-energy cutoff, once by quadrature and once by shift-and-add of the views.
Result<BestFocus> refocusToSharpest(const LightField& lightField);
// The 75%-energy cutoff of a point-source photograph (cycles per pixel), read on its spectrum
// zero-padded kCutoffZeroPadding times, so that it is not stepped by the photograph's few bins
// (a 40-pixel photograph's bins are 0.025 cycles per pixel apart).
constexpr int kCutoffZeroPadding = 8;
Result<double> cutoffOf(const Image& photo);

// ---- reports ----------------------------------------------------------------------------------

struct Series {
  std::string name;
  std::vector<double> x, y;
  bool line = true, points = true;
  bool filled = false;  // a closed polygon, shaded
};
struct Plot {
  std::string title, xLabel, yLabel;
  bool logX = false;
  std::vector<Series> series;
  std::vector<std::pair<std::string, double>> horizontalLines;  // labelled reference levels
  std::vector<std::pair<std::string, double>> verticalLines;
};
// An SVG drawing of the plot (lfcam's own, no plotting library).
std::string plotSvg(const Plot& plot);

class Report {
 public:
  explicit Report(std::string title) : title_(std::move(title)) {}
  void heading(const std::string& text);
  void paragraph(const std::string& text);
  // A table shown in the report and written as `csvName` (CSV) too.
  void table(const std::string& csvName, const std::vector<std::string>& header,
             const std::vector<std::vector<std::string>>& rows);
  void plot(const std::string& svgName, const Plot& plot, const std::string& caption);
  // An image written as PNG (8-bit, values clamped to [0, 1]).
  void image(const std::string& pngName, Image image, const std::string& caption);
  nlohmann::json& results() { return results_; }

  // report.md, report.html, results.json and every file above into `folder`, atomically.
  Status write(const std::filesystem::path& folder) const;

 private:
  struct Block {
    enum Kind { Heading, Paragraph, Table, Figure } kind;
    std::string text, file;
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
  };
  std::string title_;
  std::vector<Block> blocks_;
  std::map<std::string, std::string> textFiles_;
  std::vector<std::pair<std::string, Image>> images_;
  nlohmann::json results_ = nlohmann::json::object();
};

std::string fixed(double value, int decimals);

// One per experiment.
Status runRefocusLimit(const std::filesystem::path& folder, const ExperimentOptions& options);
Status runSnr(const std::filesystem::path& folder, const ExperimentOptions& options);
Status runSharpnessVsN(const std::filesystem::path& folder, const ExperimentOptions& options);
Status runFNumberMatch(const std::filesystem::path& folder, const ExperimentOptions& options);
Status runObserverRange(const std::filesystem::path& folder, const ExperimentOptions& options);

}  // namespace lfcam::experiments
