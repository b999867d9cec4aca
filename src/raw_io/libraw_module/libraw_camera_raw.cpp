// Camera raws through LibRaw, the module liblfcam_libraw.so (raw_io/camera_raw_codec.hpp): the
// mosaic as the sensor gave it (no demosaicing, no scaling).
#include <libraw/libraw.h>

#include <algorithm>
#include <memory>

#include <nlohmann/json.hpp>

#include "raw_io/camera_raw_codec.hpp"

namespace lfcam {

namespace {

// Bayer pattern from the colours of the top-left 2x2 (LibRaw: 0 red, 1 green, 2 blue, 3 the
// second green), or nullopt for anything else (X-Trans, four-colour sensors).
std::optional<ColorFilter> bayerPattern(LibRaw& lr) {
  int c[4];
  for (int k = 0; k < 4; ++k) {
    c[k] = lr.COLOR(k / 2, k % 2);
    if (c[k] == 3) c[k] = 1;
  }
  auto is = [&](int a, int b, int d, int e) { return c[0] == a && c[1] == b && c[2] == d && c[3] == e; };
  if (is(0, 1, 1, 2)) return ColorFilter::RGGB;
  if (is(2, 1, 1, 0)) return ColorFilter::BGGR;
  if (is(1, 0, 2, 1)) return ColorFilter::GRBG;
  if (is(1, 2, 0, 1)) return ColorFilter::GBRG;
  return std::nullopt;
}

Result<CameraRawCodes> readCodes(const std::filesystem::path& path) {
  const std::string where = path.string();
  auto lr = std::make_unique<LibRaw>();  // large: keep it off the stack
  if (int status = lr->open_file(path.c_str()); status != LIBRAW_SUCCESS)
    return makeError(status == LIBRAW_IO_ERROR ? ErrorCode::Io : ErrorCode::Format,
                     where + ": not a camera raw LibRaw reads: " + libraw_strerror(status));
  if (int status = lr->unpack(); status != LIBRAW_SUCCESS)
    return makeError(ErrorCode::Format, where + ": LibRaw cannot unpack it: " + libraw_strerror(status));
  const libraw_image_sizes_t& size = lr->imgdata.sizes;
  const unsigned short* mosaic = lr->imgdata.rawdata.raw_image;
  if (!mosaic)
    return makeError(ErrorCode::Unsupported, where +
                                                 ": not a one-value-per-photosite mosaic (linear DNG, sRAW or "
                                                 "Foveon); lfcam needs the undemosaiced sensor image");
  if (lr->imgdata.idata.filters != 0 && lr->imgdata.idata.filters < 1000)
    return makeError(ErrorCode::Unsupported, where + ": X-Trans or other non-Bayer colour filter");
  const int width = size.width, height = size.height;
  if (width < 1 || height < 1 || size.left_margin + width > size.raw_width ||
      size.top_margin + height > size.raw_height)
    return makeError(ErrorCode::Format, where + ": inconsistent raw dimensions");
  CameraRawCodes raw;
  if (lr->imgdata.idata.filters != 0) {
    auto pattern = bayerPattern(*lr);
    if (!pattern) return makeError(ErrorCode::Unsupported, where + ": colour filter other than a 2x2 Bayer pattern");
    raw.colorFilter = *pattern;
  }
  raw.width = width;
  raw.height = height;
  raw.mosaic.resize(std::size_t(width) * height);
  const std::size_t pitch = size.raw_pitch / sizeof(unsigned short);
  for (int y = 0; y < height; ++y) {
    const unsigned short* row = mosaic + std::size_t(y + size.top_margin) * pitch + size.left_margin;
    std::copy(row, row + width, raw.mosaic.begin() + std::size_t(y) * width);
  }
  const libraw_colordata_t& color = lr->imgdata.color;
  double black = color.black + 0.25 * (color.cblack[0] + color.cblack[1] + color.cblack[2] + color.cblack[3]);
  const unsigned patternCount = color.cblack[4] * color.cblack[5];
  if (patternCount > 0 && patternCount <= LIBRAW_CBLACK_SIZE - 6) {
    double sum = 0;
    for (unsigned k = 0; k < patternCount; ++k) sum += color.cblack[6 + k];
    black += sum / patternCount;
  }
  raw.blackLevel = black;
  raw.whiteLevel = color.maximum > 0 ? color.maximum : 65535;
  if (color.cam_mul[0] > 0 && color.cam_mul[1] > 0 && color.cam_mul[2] > 0)
    raw.whiteBalance =
        std::array<double, 3>{color.cam_mul[0] / color.cam_mul[1], 1.0, color.cam_mul[2] / color.cam_mul[1]};
  std::array<double, 9> matrix{};
  bool any = false;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) any |= (matrix[r * 3 + c] = color.rgb_cam[r][c]) != 0;
  if (any) raw.colorMatrix = matrix;
  raw.metadataJson = nlohmann::json{{"make", lr->imgdata.idata.make},
                                    {"model", lr->imgdata.idata.model},
                                    {"raw_size", {size.raw_width, size.raw_height}},
                                    {"margins", {size.left_margin, size.top_margin}},
                                    {"iso", lr->imgdata.other.iso_speed}}
                         .dump();
  return raw;
}

}  // namespace

}  // namespace lfcam

extern "C" const lfcam::CameraRawCodec lfcamCameraRawCodec{lfcam::readCodes};
