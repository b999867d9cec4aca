// parameters.cfg of the HCI 4D light field benchmark (Honauer et al. 2016): an INI file beside the
// views (input_CamNNN.png) stating the grid, the virtual camera and the scene's disparity range.
//
// Syntax read: `key = value` (or `key: value`) lines; `[section]` headers, blank lines and lines
// starting with '#' or ';' are skipped; keys are matched case-insensitively and sections are
// ignored (HCI keys are unique). A key given twice keeps the last value. Keys lfcam does not use
// are ignored; the ones it uses must hold a finite number within the bounds below, else a Format
// error naming the file, the line and the key. At most 1 MiB and 4096 characters a line: the file
// is small text, anything bigger is not a parameters.cfg.
//
// Optics (hciOptics): the benchmark converts disparity d (pixels per view step, positive nearer
// than the focus plane) to depth z (m, along the optical axis from the camera array) by
//     1 / z = 1 / focus_distance_m + 1000 sensor_size_mm d / (baseline_mm focal_length_mm max(w, h))
// (toolkit scenes/base_scene.py, disp2depth). The same relation holds for a plenoptic camera with
// view step du = baseline_mm, pixel ds = sensor_size_mm / max(w, h), lens-to-microlens distance
// F = focal_length_mm and a main lens focused at focus_distance_m, i.e. of focal length
// f = 1 / (1 / F + 1 / focus): light_field.hpp's slope = (du / ds) (1 - 1 / alpha) with the thin
// lens then gives 1 / z = 1 / focus + (ds / (du F)) d. So distanceFromDisparity (depth.hpp) yields
// the benchmark's depth, in millimetres.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "lfcam/core/light_field.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam {

struct HciParameters {
  // [intrinsics]
  std::optional<int> imageWidth, imageHeight;  // image_resolution_x_px, _y_px: 1 .. 1 << 20
  std::optional<double> focalLengthMm;         // focal_length_mm: > 0
  std::optional<double> sensorSizeMm;          // sensor_size_mm: > 0, across the longer side
  std::optional<double> fstop;                 // fstop: > 0
  // [extrinsics]
  std::optional<int> camerasX, camerasY;  // num_cams_x, num_cams_y: 1 .. 100000
  std::optional<double> baselineMm;       // baseline_mm: > 0, between adjacent cameras
  std::optional<double> focusDistanceM;   // focus_distance_m: > 0
  // [meta]
  std::optional<double> disparityMin, disparityMax;  // disp_min, disp_max: finite
  std::string scene;                                 // scene (free text, at most 256 characters)
};

// Parses the text of a parameters.cfg; `name` (the file) starts every error message.
Result<HciParameters> parseHciParameters(std::string_view text, const std::string& name = "parameters.cfg");
// Reads and parses a parameters.cfg file.
Result<HciParameters> readHciParameters(const std::filesystem::path& path);

// The optics that make distanceFromDisparity (depth.hpp) give the benchmark's depth (see above);
// nullopt unless focal length, sensor size, baseline, focus distance and a resolution are known.
std::optional<Optics> hciOptics(const HciParameters& parameters);

}  // namespace lfcam
