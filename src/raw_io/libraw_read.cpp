// Camera raws (libraw_read.hpp): LibRaw's part in the module liblfcam_libraw.so
// (raw_io/camera_raw_codec.hpp), loaded on the first camera raw.
#include "raw_io/libraw_read.hpp"

#include "core/lazy_module.hpp"
#include "raw_io/camera_raw_codec.hpp"

namespace lfcam {

Result<RawImage> readCameraRaw(const std::filesystem::path& path) {
  LFCAM_ASSIGN_OR_RETURN(
      void* table, lazyModuleEntry("libraw", LFCAM_CAMERA_RAW_CODEC_ENTRY, path.string() + ": reading a camera raw"));
  LFCAM_ASSIGN_OR_RETURN(auto codes, static_cast<const CameraRawCodec*>(table)->read(path));
  RawImage raw;
  raw.mosaic = Image(codes.width, codes.height, 1);
  std::copy(codes.mosaic.begin(), codes.mosaic.end(), raw.mosaic.plane(0));
  raw.colorFilter = codes.colorFilter;
  raw.blackLevel = codes.blackLevel;
  raw.whiteLevel = codes.whiteLevel;
  raw.whiteBalance = codes.whiteBalance;
  raw.colorMatrix = codes.colorMatrix;
  raw.source = "libraw";
  raw.metadataJson = std::move(codes.metadataJson);
  return raw;
}

}  // namespace lfcam
