// Decoding from files: a raw lenslet image with its white image, dark frame and grid as files, the
// way `lfcam decode`, every command that decodes a raw on the way, and the Python package take
// them. Reads each file (raw_io.hpp), checks that the frames match the raw's size, calibrates the
// grid from the white image when no grid file is given (calibrate.hpp), then decodes (decode.hpp).
// Errors name the file that is wrong.
#pragma once

#include <optional>
#include <string>

#include "lfcam/decode.hpp"
#include "lfcam/light_field.hpp"
#include "lfcam/progress.hpp"
#include "lfcam/result.hpp"
#include "lfcam/sensor_layout.hpp"

namespace lfcam {

struct RawFiles {
  std::string raw, white, dark, grid;  // grid: a grid.json; empty: calibrated from the white image
  std::optional<ColorFilter> bayer;    // overrides what the raw says
  std::optional<double> blackLevel;    // DN, overrides what the raw and white say; a dark frame wins
  DecodeOptions decode;                // its white and dark are filled from the files; optics from the raw
};

Result<LightField> decodeRawFiles(RawFiles files, const ProgressCallback& progress = {});

}  // namespace lfcam
