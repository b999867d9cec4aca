// Decoding from files: a raw lenslet image with its white image, dark frame and grid as files, the
// way `lfcam decode`, every command that decodes a raw on the way, and the Python package take
// them. Reads each file (raw_io.hpp), checks that the frames match the raw's size, calibrates the
// grid from the white image when no grid file is given (calibrate.hpp), or takes both from a
// white-image database (white_database.hpp), then decodes (decode.hpp); the light field's
// metadata.source says which white a database gave.
// Errors name the file that is wrong.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "lfcam/core/light_field.hpp"
#include "lfcam/core/progress.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/core/sensor_layout.hpp"
#include "lfcam/decode/decode.hpp"

namespace lfcam {

struct RawFiles {
  // grid: a grid.json; empty: calibrated from the white image, or without one from the raw itself
  std::string raw, white, dark, grid;
  // A white-image database (white_database.hpp) instead of white and grid: the white of the raw's
  // camera nearest its zoom and focus, with its cached grid; of any camera with anyCamera.
  std::string whites;
  bool anyCamera = false;
  std::function<void(const std::string&)> onWhiteChosen;  // told which white and why, before decoding
  std::optional<ColorFilter> bayer;                       // overrides what the raw says
  std::optional<double> blackLevel;                       // DN, overrides what the raw and white say; a dark frame wins
  DecodeOptions decode;  // its white and dark are filled from the files; optics from the raw
};

Result<LightField> decodeRawFiles(RawFiles files, const ProgressCallback& progress = {});

}  // namespace lfcam
