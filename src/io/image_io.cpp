// Image files: PNG, JPEG, TIFF and OpenEXR through io/png_file, io/jpeg_file, io/tiff_file and
// io/exr_file (their own libraries), PFM through io/pfm. Which reader runs is decided by the file's first bytes;
// which writer runs, by the name's extension.
#include "lfcam/io/image_io.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <span>
#include <string>
#include <system_error>
#include <vector>

#include "core/atomic_file.hpp"
#include "io/exr_file.hpp"
#include "io/io_support.hpp"
#include "io/jpeg_file.hpp"
#include "io/pfm.hpp"
#include "io/png_file.hpp"
#include "io/srgb.hpp"
#include "io/tiff_file.hpp"

namespace lfcam {

namespace fs = std::filesystem;
using io::fileError;

namespace {

enum class Kind { Png, Jpeg, Tiff, Exr, Pfm, Other };

std::array<unsigned char, 8> readHead(const fs::path& path, std::size_t& length) {
  std::array<unsigned char, 8> head{};
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(head.data()), head.size());
  length = std::size_t(in.gcount());
  return head;
}

// The kind of image by its signature.
Kind kindFromContent(const fs::path& path) {
  std::size_t length = 0;
  const auto h = readHead(path, length);
  const auto starts = [&](std::initializer_list<unsigned char> magic) {
    return length >= magic.size() && std::equal(magic.begin(), magic.end(), h.begin());
  };
  if (starts({0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'})) return Kind::Png;
  if (starts({0xff, 0xd8, 0xff})) return Kind::Jpeg;
  if (starts({'I', 'I', 42, 0}) || starts({'M', 'M', 0, 42}) || starts({'I', 'I', 43, 0}) || starts({'M', 'M', 0, 43}))
    return Kind::Tiff;
  if (starts({0x76, 0x2f, 0x31, 0x01})) return Kind::Exr;
  if (io::startsLikePfm(std::span(h.data(), length))) return Kind::Pfm;
  return Kind::Other;
}

Kind kindFromName(const fs::path& path) {
  const std::string extension = io::lowerExtension(path);
  if (extension == ".png") return Kind::Png;
  if (extension == ".jpg" || extension == ".jpeg") return Kind::Jpeg;
  if (extension == ".tif" || extension == ".tiff") return Kind::Tiff;
  if (extension == ".exr") return Kind::Exr;
  if (extension == ".pfm") return Kind::Pfm;
  return Kind::Other;
}

const char* sampleTypeName(SampleType type) {
  switch (type) {
    case SampleType::UInt8: return "8-bit";
    case SampleType::UInt16: return "16-bit";
    case SampleType::Float32: return "float";
  }
  return "?";
}

std::size_t bytesPerSample(SampleType type) {
  return type == SampleType::UInt8 ? 1 : type == SampleType::UInt16 ? 2 : sizeof(float);
}

// A header that promises far more pixels than the file could hold is refused before allocating.
// Deflate cannot compress better than about 1032:1, so a PNG's pixels fit in ~1100 x its size;
// no other codec of these formats (LZW, PackBits, JPEG, EXR's RLE/ZIP/PIZ) reaches 4096:1.
Status checkAgainstFileLength(const fs::path& path, Kind kind, int width, int height, int channels,
                              std::size_t bytesPerSample) {
  LFCAM_TRY(io::checkClaimFitsFile(path,
                                   checkedProduct({std::uint64_t(width), std::uint64_t(height), std::uint64_t(channels),
                                                   std::uint64_t(bytesPerSample)}),
                                   kind == Kind::Png ? 1100 : 4096,
                                   std::to_string(width) + "x" + std::to_string(height) + " pixels"));
  return io::checkSampleCount(path, {std::uint64_t(width), std::uint64_t(height), std::uint64_t(channels)});
}

// Interleaved codes to planar linear floats. 8-bit colour is sRGB; alpha is linear everywhere.
Image planarFromCodes(const unsigned char* buffer, int width, int height, int channels, int alphaChannel,
                      SampleType type) {
  const std::size_t pixels = std::size_t(width) * height;
  const auto& linearOfCode = io::linearOfSrgb8Codes();
  Image image(width, height, channels);
  for (int c = 0; c < channels; ++c) {
    float* plane = image.plane(c);
    const bool alpha = c == alphaChannel;
    if (type == SampleType::UInt8) {
      for (std::size_t i = 0; i < pixels; ++i) {
        const std::uint8_t code = buffer[i * channels + c];
        plane[i] = alpha ? code / 255.0f : linearOfCode[code];
      }
    } else if (type == SampleType::UInt16) {
      const auto* codes = reinterpret_cast<const std::uint16_t*>(buffer);
      for (std::size_t i = 0; i < pixels; ++i) plane[i] = float(codes[i * channels + c] / 65535.0);
    } else {
      const auto* values = reinterpret_cast<const float*>(buffer);
      for (std::size_t i = 0; i < pixels; ++i) plane[i] = values[i * channels + c];
    }
  }
  return image;
}

// The alpha of a PNG (and of the formats written like it) is its last channel when it has two or four.
int pngAlphaChannel(int channels) { return channels == 2 || channels == 4 ? channels - 1 : -1; }

// The formats read as interleaved samples by their own libraries (EXR and PFM are read as planes).
bool readAsCodes(Kind kind) { return kind == Kind::Png || kind == Kind::Jpeg || kind == Kind::Tiff; }

Result<io::InterleavedCodes> readCodes(const fs::path& path, Kind kind, bool pixels) {
  const auto checkHeader = [&](const io::InterleavedCodes& header) {
    return checkAgainstFileLength(path, kind, header.width, header.height, header.channels,
                                  bytesPerSample(header.type));
  };
  if (kind == Kind::Tiff) return io::readTiff(path, pixels, checkHeader);
  return kind == Kind::Png ? io::readPng(path, pixels, checkHeader) : io::readJpeg(path, pixels, checkHeader);
}

// What each writable format can hold: its natural sample type and channel counts.
struct FormatRules {
  const char* name;
  SampleType natural;
  std::vector<SampleType> types;
  int maxChannels;
  bool twoOrFourChannels;  // false: only 1 or 3 (JPEG, PFM)
};

FormatRules rulesFor(Kind kind) {
  switch (kind) {
    case Kind::Png: return {"PNG", SampleType::UInt8, {SampleType::UInt8, SampleType::UInt16}, 4, true};
    case Kind::Jpeg: return {"JPEG", SampleType::UInt8, {SampleType::UInt8}, 3, false};
    case Kind::Tiff:
      return {"TIFF", SampleType::UInt16, {SampleType::UInt8, SampleType::UInt16, SampleType::Float32}, 1024, true};
    case Kind::Exr: return {"OpenEXR", SampleType::Float32, {SampleType::Float32}, 1024, true};
    case Kind::Pfm: return {"PFM", SampleType::Float32, {SampleType::Float32}, 3, false};
    case Kind::Other: break;
  }
  return {"?", SampleType::Float32, {}, 0, false};
}

// Planar linear floats to interleaved codes of `type`.
std::vector<unsigned char> encodePixels(const Image& image, SampleType type, int alphaChannel) {
  const int channels = image.channels();
  const std::size_t pixels = image.planeSize();
  std::vector<unsigned char> buffer(pixels * channels * bytesPerSample(type));
  for (int c = 0; c < channels; ++c) {
    const float* plane = image.plane(c);
    if (type == SampleType::UInt8) {
      const bool alpha = c == alphaChannel;
      for (std::size_t i = 0; i < pixels; ++i)
        buffer[i * channels + c] = alpha ? io::unorm8FromLinear(plane[i]) : io::srgb8FromLinear(plane[i]);
    } else if (type == SampleType::UInt16) {
      auto* codes = reinterpret_cast<std::uint16_t*>(buffer.data());
      for (std::size_t i = 0; i < pixels; ++i) codes[i * channels + c] = io::unorm16FromLinear(plane[i]);
    } else {
      auto* values = reinterpret_cast<float*>(buffer.data());
      for (std::size_t i = 0; i < pixels; ++i) values[i * channels + c] = plane[i];
    }
  }
  return buffer;
}

}  // namespace

Result<Image> readImage(const fs::path& path) {
  LFCAM_TRY(io::checkReadableFile(path));
  const Kind kind = kindFromContent(path);
  if (kind == Kind::Pfm) return io::readPfm(path);
  if (kind == Kind::Exr)
    return io::readExr(path, [&](const io::ExrHeader& header) {
      return checkAgainstFileLength(path, kind, header.width, header.height, header.channels, sizeof(float));
    });
  if (!readAsCodes(kind)) return fileError(ErrorCode::Format, path, "not a readable image: unknown format");
  LFCAM_ASSIGN_OR_RETURN(auto codes, readCodes(path, kind, true));
  return planarFromCodes(codes.samples.data(), codes.width, codes.height, codes.channels,
                         kind == Kind::Tiff ? codes.alphaChannel : pngAlphaChannel(codes.channels), codes.type);
}

Result<ImageHeader> readImageHeader(const fs::path& path) {
  LFCAM_TRY(io::checkReadableFile(path));
  const Kind kind = kindFromContent(path);
  if (kind == Kind::Pfm) return io::readPfmHeader(path);
  if (kind == Kind::Exr) {
    LFCAM_ASSIGN_OR_RETURN(auto header, io::readExrHeader(path));
    return ImageHeader{header.width, header.height, header.channels, SampleType::Float32};
  }
  if (!readAsCodes(kind)) return fileError(ErrorCode::Format, path, "not a readable image: unknown format");
  LFCAM_ASSIGN_OR_RETURN(auto codes, readCodes(path, kind, false));
  return ImageHeader{codes.width, codes.height, codes.channels, codes.type};
}

Result<std::string> readImageDescription(const fs::path& path) {
  LFCAM_TRY(io::checkReadableFile(path));
  const Kind kind = kindFromContent(path);
  if (kind == Kind::Pfm) {
    LFCAM_TRY(io::readPfmHeader(path));  // PFM has no place for one; still check the file
    return std::string();
  }
  if (kind == Kind::Exr) {
    LFCAM_ASSIGN_OR_RETURN(auto header, io::readExrHeader(path));
    return header.description;
  }
  if (!readAsCodes(kind)) return fileError(ErrorCode::Format, path, "not a readable image: unknown format");
  LFCAM_ASSIGN_OR_RETURN(auto codes, readCodes(path, kind, false));
  return codes.description;
}

bool looksLikeImageFile(const fs::path& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec) && kindFromContent(path) != Kind::Other;
}

Status checkImageWriteOptions(const fs::path& path, const ImageWriteOptions& options) {
  const Kind kind = kindFromName(path);
  if (kind == Kind::Other)
    return fileError(ErrorCode::Usage, path,
                     "unknown image extension '" + path.extension().string() +
                         "' (use .png, .tif, .tiff, .exr, .jpg, .jpeg or .pfm)");
  const FormatRules rules = rulesFor(kind);
  const SampleType type = options.sampleType.value_or(rules.natural);
  if (std::find(rules.types.begin(), rules.types.end(), type) == rules.types.end())
    return fileError(ErrorCode::Usage, path,
                     std::string(rules.name) + " cannot hold " + sampleTypeName(type) + " samples");
  if (kind == Kind::Jpeg && (options.jpegQuality < 1 || options.jpegQuality > 100))
    return fileError(ErrorCode::Usage, path,
                     "JPEG quality must be in 1..100, not " + std::to_string(options.jpegQuality));
  return {};
}

Status writeImage(const fs::path& path, const Image& image, const ImageWriteOptions& options) {
  LFCAM_TRY(checkImageWriteOptions(path, options));
  if (image.empty()) return fileError(ErrorCode::Usage, path, "nothing to write: the image is empty");
  const Kind kind = kindFromName(path);
  const FormatRules rules = rulesFor(kind);
  const SampleType type = options.sampleType.value_or(rules.natural);
  const int channels = image.channels();
  if (channels > rules.maxChannels || (!rules.twoOrFourChannels && channels != 1 && channels != 3))
    return fileError(ErrorCode::Usage, path,
                     std::string(rules.name) + " cannot hold " + std::to_string(channels) + " channels");

  return writeFileAtomically(path, [&](const fs::path& temporary) -> Status {
    if (kind == Kind::Pfm) return io::writePfm(temporary, image, path);
    if (kind == Kind::Exr) return io::writeExr(temporary, path, image, options.description);
    io::InterleavedCodes codes{image.width(),
                               image.height(),
                               image.channels(),
                               type,
                               encodePixels(image, type, pngAlphaChannel(image.channels())),
                               options.description};
    if (kind == Kind::Tiff) return io::writeTiff(temporary, path, codes);
    return kind == Kind::Png ? io::writePng(temporary, path, codes)
                             : io::writeJpeg(temporary, path, codes, options.jpegQuality);
  });
}

}  // namespace lfcam
