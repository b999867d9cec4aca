#include "io/png_check.hpp"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <zlib.h>

#include "io/io_support.hpp"

namespace lfcam::io {

namespace fs = std::filesystem;

namespace {

std::uint32_t bigEndian32(const unsigned char* bytes) {
  return std::uint32_t(bytes[0]) << 24 | std::uint32_t(bytes[1]) << 16 | std::uint32_t(bytes[2]) << 8 | bytes[3];
}

// libpng's default user limit on width and height (PNG_USER_WIDTH_MAX, PNG_USER_HEIGHT_MAX).
constexpr std::uint32_t kLibpngSideLimit = 1000000;

// The IHDR fields libpng would reject with a message of its own on stderr (PNG specification,
// section 11.2.2): sizes, and the allowed pairs of bit depth and colour type.
template <class Corrupt>
Status checkHeader(const unsigned char* ihdr, const Corrupt& corrupt) {
  const std::uint32_t width = bigEndian32(ihdr), height = bigEndian32(ihdr + 4);
  const int depth = ihdr[8], colour = ihdr[9];
  if (width == 0 || height == 0 || width > kLibpngSideLimit || height > kLibpngSideLimit)
    return corrupt("corrupt PNG: its header gives a size of " + std::to_string(width) + " x " + std::to_string(height));
  const bool depthFits = (colour == 0 && (depth == 1 || depth == 2 || depth == 4 || depth == 8 || depth == 16)) ||
                         (colour == 3 && (depth == 1 || depth == 2 || depth == 4 || depth == 8)) ||
                         ((colour == 2 || colour == 4 || colour == 6) && (depth == 8 || depth == 16));
  if (!depthFits || ihdr[10] != 0 || ihdr[11] != 0 || ihdr[12] > 1)
    return corrupt("corrupt PNG: its header has an invalid bit depth, colour type, compression, filter or interlace");
  return {};
}

}  // namespace

Status checkPngStructure(const fs::path& path, bool imageData) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return fileError(ErrorCode::Io, path, "cannot open: " + std::string(std::strerror(errno)));
  std::error_code ec;
  const std::uintmax_t fileSize = fs::file_size(path, ec);
  if (ec) return fileError(ErrorCode::Io, path, "cannot read its size: " + ec.message());
  const auto corrupt = [&](const std::string& what) {
    return fileError(ErrorCode::Format, path, "not a readable image: " + what);
  };

  unsigned char signature[8];
  if (!in.read(reinterpret_cast<char*>(signature), 8)) return corrupt("truncated PNG signature");
  std::vector<unsigned char> data;
  bool first = true, sawData = false;
  for (;;) {
    unsigned char head[8];
    in.read(reinterpret_cast<char*>(head), 8);
    if (in.gcount() != 8) return corrupt("truncated PNG: the file ends before the IEND chunk");
    const std::uint32_t length = bigEndian32(head);
    const std::string type(reinterpret_cast<const char*>(head + 4), 4);
    if (length > 0x7fffffffu) return corrupt("corrupt PNG: chunk '" + type + "' has an impossible length");
    if (first && (type != "IHDR" || length != 13)) return corrupt("corrupt PNG: it does not start with IHDR");
    first = false;

    if (type == "IDAT") sawData = true;
    if (type == "IDAT" && !imageData) {  // skipped, once known to be in the file with its CRC
      const std::uintmax_t end = std::uintmax_t(in.tellg()) + length + 4;
      if (end > fileSize)
        return corrupt("truncated PNG: chunk '" + type + "' needs " + std::to_string(length) + " bytes");
      in.seekg(std::streamoff(end));
      continue;
    }
    // The CRC covers the type and the data; read the data in pieces to bound memory.
    uLong crc = crc32(0, head + 4, 4);  // zlib's: several bytes a step
    std::uint32_t left = length;
    data.resize(std::min<std::uint32_t>(length, 1u << 20));
    while (left > 0) {
      const std::uint32_t piece = std::min<std::uint32_t>(left, std::uint32_t(data.size()));
      in.read(reinterpret_cast<char*>(data.data()), piece);
      if (std::uint32_t(in.gcount()) != piece)
        return corrupt("truncated PNG: chunk '" + type + "' needs " + std::to_string(length) + " bytes");
      crc = crc32(crc, data.data(), piece);
      left -= piece;
    }
    unsigned char stored[4];
    in.read(reinterpret_cast<char*>(stored), 4);
    if (in.gcount() != 4) return corrupt("truncated PNG: chunk '" + type + "' has no CRC");
    if (bigEndian32(stored) != crc) return corrupt("corrupt PNG: chunk '" + type + "' fails its CRC check");
    if (type == "IHDR") LFCAM_TRY(checkHeader(data.data(), corrupt));
    if (type == "IEND") break;
  }
  if (!sawData) return corrupt("corrupt PNG: no image data (IDAT)");
  return {};
}

}  // namespace lfcam::io
