// Reading raw sensor images into RawImage (raw_image.hpp), and writing simulated Lytro raws.
//
// readRaw recognises its input by content:
//   - a Lytro container (.lfp, .lfr) holding a raw frame: unpacked and described by its frame
//     metadata;
//   - a PNG or TIFF lenslet image, 8 or 16 bit: values in DN (a 16-bit file holds DN directly,
//     an 8-bit file its codes 0-255). Black/white levels and the Bayer pattern come from the
//     options, else from a camera.json beside the file written by `lfcam simulate` (with the
//     lattice as the lenslet hint), else from a TIFF's DNG BlackLevel / WhiteLevel tags, else
//     black 0, white = the largest code, monochrome;
//   - a camera raw (DNG, CR2, NEF, ARW, ...) through LibRaw: the un-demosaiced mosaic of the
//     visible area, black/white levels, CFA pattern, as-shot white balance, camera -> sRGB matrix.
// Errors name the file in one line; nothing is printed.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lfcam/core/image.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/raw_io/raw_image.hpp"

namespace lfcam {

struct RawReadOptions {
  std::optional<ColorFilter> colorFilter;  // for images: the Bayer pattern (default: camera.json, else mono)
  // DN of the file, overrides what the file says. Usage error when negative, not below the white
  // level, or not below the file's largest value (every sample would be black).
  std::optional<double> blackLevel;
  std::optional<double> whiteLevel;  // DN, overrides what the file says
  bool useCameraJson = true;         // images: read camera.json beside the file
};

Result<RawImage> readRaw(const std::filesystem::path& path, const RawReadOptions& options = {});

// "RGGB", "BGGR", "GRBG", "GBRG", "mono" (any case).
std::optional<ColorFilter> parseColorFilterName(std::string_view name);

// A processed Lytro container's refocus stack (first-generation `*-stk.lfp`, Illum pictures): the
// JPEG slices as stored, each with the focus (lambda) it was made at, by increasing lambda, and the
// container's depth map in lambda (empty when it holds none), row by row as the slices. Format
// error when it holds fewer than two JPEG slices with a lambda (e.g. H.264 stacks: `lfcam extract`
// writes those out).
struct LytroRefocusSlice {
  double lambda = 0;
  std::vector<std::uint8_t> jpeg;
};
struct LytroRefocusStack {
  std::vector<LytroRefocusSlice> slices;
  Image depth;
};
Result<LytroRefocusStack> readLytroRefocusStack(const std::filesystem::path& path);

enum class LytroStyle { FirstGeneration, Illum };  // .lfp (F01) or .lfr (Illum)

struct LytroWriteOptions {
  LytroStyle style = LytroStyle::FirstGeneration;
  double pixelPitchMm = 0.0014;  // the Lytro sensors' 1.4 um unless the caller knows better
  bool modulationFrame = false;  // a white image (Lytro's "modulation" frame)
  std::string extraJson;         // a JSON value stored in the frame metadata under "lfcam" when not empty
  // The camera's serial (private metadata; default "lfcam-simulator") and lens setting
  // (devices.lens.zoomStep, focusStep; devices.shutter.frameExposureDuration), as the cameras write them.
  CameraSetting setting;
};

// A Lytro container holding `raw` (integer DN in [0, 65535]) with real-style metadata: F01 style
// packs 12-bit big-endian when every value fits 12 bits, Illum style 10-bit little-endian when they
// fit 10 bits; otherwise 16-bit little-endian (as Lytro's own simulator wrote). readRaw of the file
// returns the same mosaic, levels, Bayer pattern, lenslet hint, white balance, colour matrix and setting.
Status writeLytroRaw(const std::filesystem::path& path, const RawImage& raw, const LytroWriteOptions& options);

// `lfcam simulate --container`: from raw.png (or .tiff), white.* and camera.json in `folder`,
// writes raw.lfp (first generation) or raw.lfr and white.lfr (Illum) beside them.
Status writeSimulationContainers(const std::filesystem::path& folder, LytroStyle style);

}  // namespace lfcam
