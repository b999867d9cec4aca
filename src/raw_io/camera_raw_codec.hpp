// The LibRaw half of reading camera raws: it lives in the module liblfcam_libraw.so
// (src/raw_io/libraw_module/), loaded by libraw_read.cpp on the first camera raw
// (core/lazy_module.hpp), so that no other command maps LibRaw. Only types defined in headers
// cross the boundary: the mosaic comes as codes, and libraw_read.cpp makes the RawImage.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/core/result.hpp"
#include "lfcam/raw_io/raw_image.hpp"

namespace lfcam {

struct CameraRawCodes {
  int width = 0, height = 0;
  std::vector<std::uint16_t> mosaic;  // width x height photosites, rows top to bottom, margins cut
  ColorFilter colorFilter = ColorFilter::Mono;
  double blackLevel = 0, whiteLevel = 65535;  // DN
  std::optional<std::array<double, 3>> whiteBalance;
  std::optional<std::array<double, 9>> colorMatrix;
  std::string metadataJson;  // RawImage::metadataJson
};

struct CameraRawCodec {
  // Errors name the file.
  Result<CameraRawCodes> (*read)(const std::filesystem::path& file);
};

}  // namespace lfcam

// The module's one export: its table.
#define LFCAM_CAMERA_RAW_CODEC_ENTRY "lfcamCameraRawCodec"
