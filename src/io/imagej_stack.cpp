#include "io/imagej_stack.hpp"

#include <tiffio.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "io/io_support.hpp"
#include "io/tiff_file.hpp"

namespace lfcam::io {

namespace fs = std::filesystem;

namespace {

// lfcam's own lines in ImageJ's description, which ImageJ ignores: the depth of slice 0 has no
// place in ImageJ's calibration, and the resolution tags round the voxel's sizes to floats.
constexpr const char* kFirstSliceKey = "lfcam_first_slice_um";
constexpr const char* kVoxelWidthKey = "lfcam_voxel_width_um";
constexpr const char* kVoxelHeightKey = "lfcam_voxel_height_um";

// ImageJ's own description of a z-stack, as tifffile writes it for `imagej=True`; min and max set
// Fiji's display range.
std::string imageJDescription(const Volume& volume) {
  float low = std::numeric_limits<float>::infinity(), high = -low;
  for (float value : volume.voxels())
    if (std::isfinite(value)) low = std::min(low, value), high = std::max(high, value);
  if (low > high) low = high = 0;
  const std::string slices = std::to_string(volume.depth());
  return "ImageJ=1.11a\nimages=" + slices + "\nslices=" + slices +
         "\nunit=micron\nspacing=" + shortestNumber(volume.voxelDepthUm) + "\nloop=false\nmin=" + shortestNumber(low) +
         "\nmax=" + shortestNumber(high) + "\n" + kFirstSliceKey + "=" + shortestNumber(volume.firstSliceUm) + "\n" +
         kVoxelWidthKey + "=" + shortestNumber(volume.voxelWidthUm) + "\n" + kVoxelHeightKey + "=" +
         shortestNumber(volume.voxelHeightUm) + "\n";
}

// ImageJ's description is a Java properties text, "key=value" a line, behind "ImageJ=...".
std::map<std::string, std::string, std::less<>> imageJProperties(std::string_view description) {
  std::map<std::string, std::string, std::less<>> properties;
  if (!description.starts_with("ImageJ=")) return properties;
  while (!description.empty()) {
    const std::size_t end = std::min(description.find('\n'), description.size());
    std::string_view line = description.substr(0, end);
    description.remove_prefix(std::min(end + 1, description.size()));
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.remove_suffix(1);
    if (const std::size_t equals = line.find('='); equals != std::string_view::npos)
      properties.emplace(line.substr(0, equals), line.substr(equals + 1));
  }
  return properties;
}

std::optional<double> numberOf(const std::map<std::string, std::string, std::less<>>& properties,
                               std::string_view key) {
  const auto found = properties.find(key);
  if (found == properties.end()) return std::nullopt;
  double value = 0;
  const std::string& text = found->second;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

// Micrometres in one of ImageJ's length units; unset for "pixel" and units lfcam does not know.
std::optional<double> micrometresPer(std::string_view unit) {
  if (unit == "micron" || unit == "microns" || unit == "um" || unit == "\u00b5m" || unit == "\\u00B5m") return 1.0;
  if (unit == "nm") return 1e-3;
  if (unit == "mm") return 1e3;
  if (unit == "cm") return 1e4;
  if (unit == "m" || unit == "meter") return 1e6;
  if (unit == "inch") return 25400.0;
  return std::nullopt;
}

bool positive(std::optional<double> value) { return value && *value > 0; }

// The voxel size from ImageJ's calibration and the resolution tags, each where the file has it.
Status calibrate(const fs::path& path, const TiffStack& stack, Volume& volume) {
  const auto properties = imageJProperties(stack.header.description);
  const std::optional<double> channels = numberOf(properties, "channels"), frames = numberOf(properties, "frames");
  if (channels.value_or(1) > 1 || frames.value_or(1) > 1)
    return fileError(ErrorCode::Unsupported, path,
                     "an ImageJ hyperstack of " + shortestNumber(channels.value_or(1)) + " channels and " +
                         shortestNumber(frames.value_or(1)) + " frames; lfcam reads a volume's z-stack");
  // Without a unit (napari-LF's files, ImageJ's uncalibrated ones) numbers are taken as micrometres.
  const auto unit = properties.find("unit");
  const std::optional<double> scale = unit == properties.end() ? 1.0 : micrometresPer(unit->second);
  const std::uint16_t tiffUnit = stack.resolution ? stack.resolution->unit : 0;
  const std::optional<double> unitUm = tiffUnit == RESUNIT_CENTIMETER ? 1e4
                                       : tiffUnit == RESUNIT_INCH     ? 25400.0
                                                                      : scale;
  if (const auto width = numberOf(properties, kVoxelWidthKey); positive(width))
    volume.voxelWidthUm = *width;
  else if (stack.resolution && stack.resolution->x > 0 && unitUm)
    volume.voxelWidthUm = *unitUm / stack.resolution->x;
  // A file without the height (an earlier lfcam's, square voxels) has the width's.
  if (const auto height = numberOf(properties, kVoxelHeightKey); positive(height))
    volume.voxelHeightUm = *height;
  else if (stack.resolution && stack.resolution->y > 0 && unitUm)
    volume.voxelHeightUm = *unitUm / stack.resolution->y;
  else
    volume.voxelHeightUm = volume.voxelWidthUm;
  if (const auto spacing = numberOf(properties, "spacing"); scale && positive(spacing))
    volume.voxelDepthUm = *spacing * *scale;
  volume.firstSliceUm = numberOf(properties, kFirstSliceKey).value_or(0);
  return {};
}

// Page `codes` into `slice`: codes scaled to [0, 1], floats as they are.
void copyPage(const InterleavedCodes& codes, float* slice) {
  const std::size_t count = std::size_t(codes.width) * codes.height;
  if (codes.type == SampleType::Float32) {
    std::memcpy(slice, codes.samples.data(), count * sizeof(float));
  } else if (codes.type == SampleType::UInt16) {
    const auto* values = reinterpret_cast<const std::uint16_t*>(codes.samples.data());
    for (std::size_t i = 0; i < count; ++i) slice[i] = float(values[i] / 65535.0);
  } else {
    for (std::size_t i = 0; i < count; ++i) slice[i] = float(codes.samples[i] / 255.0);
  }
}

}  // namespace

// Pages deflated, as writeTiffStack writes them, on purpose: ImageJ reads an uncompressed stack
// whose description says images= as one contiguous block after the first page, which libtiff's
// pages are not; a compressed one it reads page by page.
Status writeImageJStack(const fs::path& temporary, const fs::path& path, const Volume& volume) {
  const TiffStack stack{
      .header = {volume.width(), volume.height(), 1, SampleType::Float32, {}, imageJDescription(volume)},
      .pages = volume.depth(),
      .resolution = TiffResolution{1 / volume.voxelWidthUm, 1 / volume.voxelHeightUm, RESUNIT_NONE}};
  return writeTiffStack(temporary, path, stack,
                        [&](int z) { return reinterpret_cast<const unsigned char*>(volume.slice(z)); });
}

Result<Volume> readTiffVolume(const fs::path& path) {
  Volume volume;
  const auto start = [&](const TiffStack& stack) -> Status {
    const InterleavedCodes& page = stack.header;
    if (page.channels != 1)
      return fileError(ErrorCode::Unsupported, path,
                       "pages of " + std::to_string(page.channels) + " channels; a volume's pages hold one");
    const std::uint64_t width = page.width, height = page.height, depth = stack.pages;
    const std::uint64_t sampleBytes = page.type == SampleType::Float32 ? 4 : page.type == SampleType::UInt16 ? 2 : 1;
    LFCAM_TRY(checkClaimFitsFile(
        path, checkedProduct({width, height, depth, sampleBytes}), 4096,
        std::to_string(width) + "x" + std::to_string(height) + "x" + std::to_string(depth) + " voxels"));
    LFCAM_TRY(checkSampleCount(path, {width, height, depth}));
    volume = Volume(page.width, page.height, stack.pages);
    return calibrate(path, stack, volume);
  };
  LFCAM_TRY(readTiffStack(path, start, [&](int z, const InterleavedCodes& codes) {
    copyPage(codes, volume.slice(z));
    return Status();
  }));
  return volume;
}

}  // namespace lfcam::io
