#include "image_output.hpp"

namespace lfcam::cli {

CLI::Option* addBitDepthOption(CLI::App& command, std::string& depth) {
  return command
      .add_option("--bit-depth", depth,
                  "8 (sRGB codes, quick looks), 16 (linear radiance, 65535 = white level, PNG/TIFF) or float "
                  "(linear radiance, TIFF/EXR); default: 8 for .png/.jpg, 16 for .tif, float for .exr/.pfm")
      ->check(CLI::IsMember({"8", "16", "float"}));
}

std::optional<SampleType> sampleTypeOfDepth(const std::string& depth) {
  if (depth == "8") return SampleType::UInt8;
  if (depth == "16") return SampleType::UInt16;
  if (depth == "float") return SampleType::Float32;
  return std::nullopt;
}

Result<ImageWriteOptions> imageWriteOptionsFor(const std::filesystem::path& file, const std::string& depth) {
  const ImageWriteOptions options{.sampleType = sampleTypeOfDepth(depth)};
  LFCAM_TRY(checkImageWriteOptions(file, options));
  return options;
}

}  // namespace lfcam::cli
