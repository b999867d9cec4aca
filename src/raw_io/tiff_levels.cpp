#include "raw_io/tiff_levels.hpp"

#include <cstdint>
#include <fstream>
#include <vector>

namespace lfcam {

namespace {

constexpr std::uint16_t kBlackLevelTag = 50714, kWhiteLevelTag = 50717;
constexpr std::uint16_t kShort = 3, kLong = 4, kRational = 5;
// A level pattern is at most a few values per channel; more is a damaged directory.
constexpr std::uint32_t kMaxValues = 1024;

class TiffReader {
 public:
  explicit TiffReader(const std::filesystem::path& path) : in_(path, std::ios::binary) {}

  bool readHeader(std::uint32_t& firstDirectory) {
    char order[2];
    if (!in_.read(order, 2)) return false;
    if (order[0] == 'I' && order[1] == 'I')
      bigEndian_ = false;
    else if (order[0] == 'M' && order[1] == 'M')
      bigEndian_ = true;
    else
      return false;
    std::uint16_t magic = 0;
    return read16(magic) && magic == 42 && read32(firstDirectory);
  }

  bool seek(std::uint32_t offset) { return bool(in_.seekg(offset)); }
  bool read16(std::uint16_t& value) { return readUnsigned(2, value); }
  bool read32(std::uint32_t& value) { return readUnsigned(4, value); }

 private:
  template <class T>
  bool readUnsigned(int bytes, T& value) {
    unsigned char b[4];
    if (!in_.read(reinterpret_cast<char*>(b), bytes)) return false;
    value = 0;
    for (int i = 0; i < bytes; ++i) value |= T(b[bigEndian_ ? i : bytes - 1 - i]) << (8 * (bytes - 1 - i));
    return true;
  }

  std::ifstream in_;
  bool bigEndian_ = false;
};

// The mean of a SHORT, LONG or RATIONAL tag's values (stored in the entry when they fit 4 bytes).
std::optional<double> meanOfEntry(TiffReader& reader, std::uint16_t type, std::uint32_t count,
                                  std::uint32_t valueOrOffset, std::uint32_t entryValueAt) {
  const std::uint32_t size = type == kShort ? 2 : type == kLong ? 4 : type == kRational ? 8 : 0;
  if (size == 0 || count == 0 || count > kMaxValues) return std::nullopt;
  if (!reader.seek(size * count <= 4 ? entryValueAt : valueOrOffset)) return std::nullopt;
  double sum = 0;
  for (std::uint32_t k = 0; k < count; ++k) {
    if (type == kShort) {
      std::uint16_t v = 0;
      if (!reader.read16(v)) return std::nullopt;
      sum += v;
    } else {
      std::uint32_t numerator = 0, denominator = 1;
      if (!reader.read32(numerator) || (type == kRational && !reader.read32(denominator))) return std::nullopt;
      if (denominator == 0) return std::nullopt;
      sum += double(numerator) / denominator;
    }
  }
  return sum / count;
}

}  // namespace

TiffLevels readTiffLevels(const std::filesystem::path& path) {
  TiffLevels levels;
  TiffReader reader(path);
  std::uint32_t directory = 0;
  std::uint16_t entries = 0;
  if (!reader.readHeader(directory) || !reader.seek(directory) || !reader.read16(entries)) return levels;
  for (std::uint32_t i = 0; i < entries; ++i) {
    const std::uint32_t entryAt = directory + 2 + 12 * i;
    std::uint16_t tag = 0, type = 0;
    std::uint32_t count = 0, value = 0;
    if (!reader.seek(entryAt) || !reader.read16(tag) || !reader.read16(type) || !reader.read32(count) ||
        !reader.read32(value))
      return levels;
    if (tag == kBlackLevelTag) levels.black = meanOfEntry(reader, type, count, value, entryAt + 8);
    if (tag == kWhiteLevelTag) levels.white = meanOfEntry(reader, type, count, value, entryAt + 8);
  }
  return levels;
}

}  // namespace lfcam
