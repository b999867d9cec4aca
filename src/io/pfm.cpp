#include "io/pfm.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "io/io_support.hpp"

namespace lfcam::io {

namespace fs = std::filesystem;

namespace {

struct PfmLayout {
  int width = 0, height = 0, channels = 0;
  bool bigEndian = false;
  std::uint64_t dataOffset = 0;  // bytes of header
  std::uint64_t dataBytes = 0;   // bytes of pixels the header promises
};

bool isSpace(unsigned char ch) { return ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r'; }

// Parses the header from the first bytes of the file and checks it against the file's length,
// before anything is allocated.
Result<PfmLayout> parseHeader(const fs::path& path) {
  LFCAM_TRY(checkReadableFile(path));
  std::ifstream in(path, std::ios::binary);
  if (!in) return fileError(ErrorCode::Io, path, "cannot open: " + std::string(std::strerror(errno)));
  char buffer[256] = {};
  in.read(buffer, sizeof buffer);
  const std::size_t length = std::size_t(in.gcount());
  const auto bad = [&](const std::string& what) {
    return fileError(ErrorCode::Format, path, "not a valid PFM: " + what);
  };

  PfmLayout layout;
  if (length < 3 || buffer[0] != 'P' || (buffer[1] != 'F' && buffer[1] != 'f') || !isSpace(buffer[2]))
    return bad("it does not start with PF or Pf");
  layout.channels = buffer[1] == 'F' ? 3 : 1;

  std::size_t at = 2;
  const auto token = [&]() -> std::string_view {
    while (at < length && isSpace(buffer[at])) ++at;
    const std::size_t begin = at;
    while (at < length && !isSpace(buffer[at])) ++at;
    return {buffer + begin, at - begin};
  };
  const auto dimension = [&](std::string_view text, int& value) {
    long long parsed = 0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), parsed);
    if (ec != std::errc() || end != text.data() + text.size() || parsed <= 0 || parsed > INT32_MAX) return false;
    value = int(parsed);
    return true;
  };
  const std::string_view widthText = token(), heightText = token();
  if (!dimension(widthText, layout.width) || !dimension(heightText, layout.height))
    return bad("bad width or height '" + std::string(widthText) + " " + std::string(heightText) + "'");
  const std::string_view scaleText = token();
  double scale = 0;
  auto [end, ec] = std::from_chars(scaleText.data(), scaleText.data() + scaleText.size(), scale);
  if (ec != std::errc() || end != scaleText.data() + scaleText.size() || scale == 0 || !std::isfinite(scale))
    return bad("bad scale '" + std::string(scaleText) + "' (its sign gives the byte order)");
  if (at >= length) return bad("header too long or file ends in the header");
  layout.bigEndian = scale > 0;
  layout.dataOffset = at + 1;  // exactly one whitespace character ends the header

  const auto bytes = checkedProduct(
      {std::uint64_t(layout.width), std::uint64_t(layout.height), std::uint64_t(layout.channels), sizeof(float)});
  std::error_code sizeError;
  const std::uint64_t fileSize = fs::file_size(path, sizeError);
  if (sizeError) return fileError(ErrorCode::Io, path, "cannot read size: " + sizeError.message());
  const std::uint64_t found = fileSize > layout.dataOffset ? fileSize - layout.dataOffset : 0;
  if (!bytes || *bytes > found)
    return fileError(ErrorCode::Format, path,
                     "truncated: expected " + (bytes ? std::to_string(*bytes) : std::string("more than 2^64")) +
                         " bytes of pixels, found " + std::to_string(found));
  layout.dataBytes = *bytes;
  LFCAM_TRY(checkSampleCount(
      path, {std::uint64_t(layout.width), std::uint64_t(layout.height), std::uint64_t(layout.channels)}));
  return layout;
}

}  // namespace

bool startsLikePfm(std::span<const unsigned char> head) {
  return head.size() >= 3 && head[0] == 'P' && (head[1] == 'F' || head[1] == 'f') && isSpace(head[2]);
}

Result<ImageHeader> readPfmHeader(const fs::path& path) {
  LFCAM_ASSIGN_OR_RETURN(auto layout, parseHeader(path));
  return ImageHeader{layout.width, layout.height, layout.channels, SampleType::Float32};
}

Result<Image> readPfm(const fs::path& path) {
  LFCAM_ASSIGN_OR_RETURN(auto parsed, parseHeader(path));
  const PfmLayout& layout = parsed;

  std::vector<float> interleaved(layout.dataBytes / sizeof(float));
  std::ifstream in(path, std::ios::binary);
  in.seekg(std::streamoff(layout.dataOffset));
  in.read(reinterpret_cast<char*>(interleaved.data()), std::streamsize(layout.dataBytes));
  if (std::uint64_t(in.gcount()) != layout.dataBytes)
    return fileError(ErrorCode::Io, path, "cannot read pixels: " + std::string(std::strerror(errno)));

  if (layout.bigEndian != (std::endian::native == std::endian::big))
    for (float& value : interleaved) {
      std::uint32_t bits;
      std::memcpy(&bits, &value, sizeof bits);
      bits = __builtin_bswap32(bits);
      std::memcpy(&value, &bits, sizeof bits);
    }

  // Rows run bottom to top in the file.
  Image image(layout.width, layout.height, layout.channels);
  const std::size_t rowValues = std::size_t(layout.width) * layout.channels;
  for (int y = 0; y < layout.height; ++y) {
    const float* fileRow = interleaved.data() + std::size_t(layout.height - 1 - y) * rowValues;
    for (int c = 0; c < layout.channels; ++c) {
      float* row = image.row(y, c);
      for (int x = 0; x < layout.width; ++x) row[x] = fileRow[std::size_t(x) * layout.channels + c];
    }
  }
  return image;
}

Status writePfm(const fs::path& file, const Image& image, const fs::path& path) {
  if (image.channels() != 1 && image.channels() != 3)
    return fileError(ErrorCode::Usage, path, "PFM holds 1 or 3 channels, not " + std::to_string(image.channels()));
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) return fileError(ErrorCode::Io, path, "cannot create: " + std::string(std::strerror(errno)));
  const bool little = std::endian::native == std::endian::little;
  out << (image.channels() == 3 ? "PF" : "Pf") << '\n'
      << image.width() << ' ' << image.height() << '\n'
      << (little ? "-1.0" : "1.0") << '\n';
  std::vector<float> row(std::size_t(image.width()) * image.channels());
  for (int y = image.height() - 1; y >= 0; --y) {
    for (int c = 0; c < image.channels(); ++c) {
      const float* plane = image.row(y, c);
      for (int x = 0; x < image.width(); ++x) row[std::size_t(x) * image.channels() + c] = plane[x];
    }
    out.write(reinterpret_cast<const char*>(row.data()), std::streamsize(row.size() * sizeof(float)));
  }
  out.close();
  if (!out) return fileError(ErrorCode::Io, path, "cannot write: " + std::string(std::strerror(errno)));
  return {};
}

}  // namespace lfcam::io
