// A 16-bit greyscale TIFF carrying the DNG BlackLevel and WhiteLevel tags, as machine-vision and
// microscope software writes them, built byte by byte so that the file does not come from the
// library whose reading the tests check (libtiff), in either byte order and tag type.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/core/image.hpp"
#include "test_support.hpp"

namespace lfcam::test {

struct TiffLevelTags {
  std::vector<double> black;  // one value, or a pattern (e.g. one per 2x2 phase)
  std::optional<double> white;
  bool rational = false;  // BlackLevel as RATIONAL (thousandths) instead of SHORT
  bool bigEndian = false;
};

// Writes `codes` (one channel, values 0-65535) as an uncompressed 16-bit TIFF with `tags`.
inline void writeTiffWithLevels(const std::filesystem::path& path, const Image& codes, const TiffLevelTags& tags) {
  std::string bytes;
  const auto put = [&](std::uint32_t value, int size) {
    for (int i = 0; i < size; ++i) {
      const int shift = 8 * (tags.bigEndian ? size - 1 - i : i);
      bytes += char((value >> shift) & 0xff);
    }
  };
  struct Entry {
    std::uint16_t tag, type;
    std::uint32_t count;
    std::vector<std::uint32_t> values;  // SHORT or LONG values, or RATIONAL numerator/denominator pairs
  };
  const std::uint32_t width = std::uint32_t(codes.width()), height = std::uint32_t(codes.height());
  std::vector<Entry> entries = {{256, 4, 1, {width}}, {257, 4, 1, {height}}, {258, 3, 1, {16}},
                                {259, 3, 1, {1}},     {262, 3, 1, {1}},      {273, 4, 1, {0}},
                                {277, 3, 1, {1}},     {278, 4, 1, {height}}, {279, 4, 1, {width * height * 2}}};
  if (!tags.black.empty()) {
    Entry black{50714, std::uint16_t(tags.rational ? 5 : 3), std::uint32_t(tags.black.size()), {}};
    for (double value : tags.black) {
      if (tags.rational)
        black.values.insert(black.values.end(), {std::uint32_t(std::lround(value * 1000)), 1000});
      else
        black.values.push_back(std::uint32_t(value));
    }
    entries.push_back(black);
  }
  if (tags.white) entries.push_back({50717, 4, 1, {std::uint32_t(*tags.white)}});
  const auto sizeOf = [](const Entry& e) {
    return std::uint32_t(e.type == 3 ? 2 : 4) * std::uint32_t(e.values.size());
  };

  // Header, directory, values too long for their entry, then the pixels.
  const std::uint32_t directory = 8, afterDirectory = directory + 2 + 12 * std::uint32_t(entries.size()) + 4;
  std::uint32_t extra = afterDirectory;
  std::vector<std::uint32_t> offsets;
  for (const Entry& e : entries) {
    offsets.push_back(sizeOf(e) > 4 ? extra : 0);
    if (sizeOf(e) > 4) extra += sizeOf(e);
  }
  entries[5].values = {extra};  // StripOffsets: the pixels follow the long values
  bytes += tags.bigEndian ? "MM" : "II";
  put(42, 2);
  put(directory, 4);
  put(std::uint32_t(entries.size()), 2);
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const Entry& e = entries[k];
    put(e.tag, 2);
    put(e.type, 2);
    put(e.count, 4);
    if (sizeOf(e) > 4) {
      put(offsets[k], 4);
    } else {
      const int size = e.type == 3 ? 2 : 4;
      for (std::uint32_t v : e.values) put(v, size);
      for (std::uint32_t filled = sizeOf(e); filled < 4; ++filled) bytes += '\0';
    }
  }
  put(0, 4);  // no next directory
  for (const Entry& e : entries)
    if (sizeOf(e) > 4)
      for (std::uint32_t v : e.values) put(v, e.type == 3 ? 2 : 4);
  for (float value : codes.pixels()) put(std::uint32_t(std::clamp(value, 0.0f, 65535.0f)), 2);
  writeBytes(path, bytes);
}

}  // namespace lfcam::test
