// Image files: PNG (8/16-bit), TIFF (8/16-bit, float), OpenEXR, JPEG through their own libraries,
// and PFM (the HCI benchmark's disparity maps) by lfcam's own small reader and writer.
//
// Values in memory are linear light. 8-bit files are taken to hold sRGB-encoded values: reading
// decodes them to linear, writing encodes (the round trip of 8-bit codes is exact). 16-bit and
// float files hold linear values as they are; integer codes are scaled to [0, 1]. Writing clamps
// integer outputs to [0, 1].
//
// Every writer goes through writeFileAtomically: no partial file on failure.
#pragma once

#include <filesystem>
#include <optional>
#include <span>
#include <string>

#include "lfcam/core/image.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam {

enum class SampleType { UInt8, UInt16, Float32 };

struct ImageWriteOptions {
  // Default: the format's natural type: 8-bit for PNG and JPEG, 16-bit for TIFF, float for EXR
  // and PFM. Asking for a type the format cannot hold is a Usage error.
  std::optional<SampleType> sampleType;
  int jpegQuality = 95;
  // Stored in the file's description field (PNG text chunk, TIFF ImageDescription, EXR and
  // JPEG comments), and read back by readImageDescription.
  std::string description;
};

Result<Image> readImage(const std::filesystem::path& path);
Status writeImage(const std::filesystem::path& path, const Image& image, const ImageWriteOptions& options = {});
// What writeImage checks before it writes, short of the image itself: a known extension, a sample
// type the format holds, a JPEG quality in range. Lets a command refuse an output before its work.
Status checkImageWriteOptions(const std::filesystem::path& path, const ImageWriteOptions& options = {});

// The description field written by writeImage (empty when the file has none).
Result<std::string> readImageDescription(const std::filesystem::path& path);

// Width, height and channels without reading the pixels.
struct ImageHeader {
  int width = 0, height = 0, channels = 0;
  SampleType sampleType = SampleType::UInt8;
};
Result<ImageHeader> readImageHeader(const std::filesystem::path& path);

// True when the file starts like an image lfcam can read (by content, not by name).
bool looksLikeImageFile(const std::filesystem::path& path);

// sRGB transfer function (IEC 61966-2-1), per value.
float linearFromSrgb(float encoded);
float srgbFromLinear(float linear);
// Each value replaced by srgbFromLinear of it, at a fraction of the time (SIMD; the same floats but
// where the exact value lies within about 1e-15 of a rounding boundary, then a float step apart).
void srgbFromLinear(std::span<float> values);

}  // namespace lfcam
