// Lytro frame metadata (the JSON that describes a raw frame) <-> what lfcam needs to read it.
//
// Two real layouts are read (examples in ../shared/data/lytro-metadata/):
//   first generation (F01) and Illum white images: image.rawDetails.{pixelFormat, pixelPacking,
//     mosaic}, image.color.{ccmRgbToSrgbArray, whiteBalanceGain};
//   Illum pictures ("lightning" schema): image.{pixelFormat, pixelPacking, mosaic},
//     image.color.{ccm, whiteBalanceGain};
// and both: image.{width, height}, devices.sensor.pixelPitch (m), devices.mla.{lensPitch (m),
// rotation (rad), sensorOffset (m), tiling}. Wrapped documents (master.picture.frameArray[0].
// frame.metadata, frames[0].frame.metadata, ...) are unwrapped by findLytroFrameMetadata.
#pragma once

#include <array>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "lfcam/core/result.hpp"
#include "lfcam/core/sensor_layout.hpp"
#include "lfcam/raw_io/raw_image.hpp"
#include "lfcam/raw_io/raw_io.hpp"
#include "raw_io/raw_packing.hpp"

namespace lfcam {

struct LytroFrameFormat {
  int width = 0, height = 0;
  RawPacking packing = RawPacking::Bits16LittleEndian;
  ColorFilter colorFilter = ColorFilter::Mono;
  double blackLevel = 0, whiteLevel = 1;  // DN (the mean over the four Bayer channels)
  std::optional<double> pixelPitchM;
  std::optional<LensletHint> lenslet;  // pitchPx = lensPitch / pixelPitch; offset = sensorOffset / pixelPitch
  std::optional<std::array<double, 3>> whiteBalance;  // r, (gr + gb) / 2, b
  std::optional<std::array<double, 9>> colorMatrix;   // camera RGB -> sRGB, row-major
  std::string camera;                                 // make and model, when given
};

// The frame metadata object inside `document`: the document itself when it has "image", else
// the first of master.picture.frameArray[0].frame.metadata, picture.frameArray[0].frame.metadata,
// frames[0].frame.metadata. nullptr when none.
const nlohmann::json* findLytroFrameMetadata(const nlohmann::json& document);

// `where` starts every error (a file name). Missing width, height, packing or an unknown
// packing is an error; everything else is optional.
Result<LytroFrameFormat> parseLytroFrameMetadata(const nlohmann::json& metadata, const std::string& where);

// Bayer pattern from Lytro's mosaic description (tile "r,gr:gb,b" and the upper-left pixel, or
// tile "monochrome").
std::optional<ColorFilter> lytroMosaicFilter(const nlohmann::json& mosaic);

// Frame metadata in the layout of `style` describing `format` (the writer's side of
// parseLytroFrameMetadata: reading it back gives `format` again).
nlohmann::json makeLytroFrameMetadata(const LytroFrameFormat& format, LytroStyle style);

}  // namespace lfcam
