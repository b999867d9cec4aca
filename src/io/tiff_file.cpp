#include "io/tiff_file.hpp"

#include <tiffio.h>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "io/io_support.hpp"

namespace lfcam::io {

namespace fs = std::filesystem;

namespace {

// libtiff reports through handlers: the first error is kept for the message (the handler's
// non-zero answer keeps libtiff from printing it), warnings are dropped; reads still fail on damage.
int keepFirstError(TIFF*, void* messages, const char*, const char* format, va_list arguments) {
  auto& first = *static_cast<std::string*>(messages);
  if (first.empty()) {
    char text[512];
    std::vsnprintf(text, sizeof text, format, arguments);
    first = text;
  }
  return 1;
}
int dropWarning(TIFF*, void*, const char*, const char*, va_list) { return 1; }

struct TiffCloser {
  void operator()(TIFF* tiff) const { TIFFClose(tiff); }
};
using TiffHandle = std::unique_ptr<TIFF, TiffCloser>;

// `messages` must outlive the handle: libtiff reports into it until the file is closed.
TiffHandle openTiff(const fs::path& path, const char* mode, std::string& messages) {
  TIFFOpenOptions* options = TIFFOpenOptionsAlloc();
  TIFFOpenOptionsSetErrorHandlerExtR(options, keepFirstError, &messages);
  TIFFOpenOptionsSetWarningHandlerExtR(options, dropWarning, nullptr);
  TiffHandle tiff(TIFFOpenExt(path.c_str(), mode, options));
  TIFFOpenOptionsFree(options);
  return tiff;
}

std::string reasonOr(const std::string& messages, const char* fallback) {
  return messages.empty() ? fallback : messages;
}

// The layout of the first image's samples as the file stores them.
struct Layout {
  std::uint32_t width = 0, height = 0;
  std::uint16_t bits = 1, channels = 1, format = SAMPLEFORMAT_UINT, photometric = PHOTOMETRIC_MINISBLACK;
  bool separatePlanes = false;
  int alphaChannel = -1;
};

Layout layoutOf(TIFF* tiff) {
  Layout layout;
  std::uint16_t planar = PLANARCONFIG_CONTIG;
  TIFFGetField(tiff, TIFFTAG_IMAGEWIDTH, &layout.width);
  TIFFGetField(tiff, TIFFTAG_IMAGELENGTH, &layout.height);
  TIFFGetFieldDefaulted(tiff, TIFFTAG_BITSPERSAMPLE, &layout.bits);
  TIFFGetFieldDefaulted(tiff, TIFFTAG_SAMPLESPERPIXEL, &layout.channels);
  TIFFGetFieldDefaulted(tiff, TIFFTAG_SAMPLEFORMAT, &layout.format);
  TIFFGetFieldDefaulted(tiff, TIFFTAG_PLANARCONFIG, &planar);
  TIFFGetField(tiff, TIFFTAG_PHOTOMETRIC, &layout.photometric);
  layout.separatePlanes = planar == PLANARCONFIG_SEPARATE && layout.channels > 1;
  std::uint16_t extraCount = 0;
  std::uint16_t* extraTypes = nullptr;
  if (TIFFGetField(tiff, TIFFTAG_EXTRASAMPLES, &extraCount, &extraTypes) && extraCount <= layout.channels)
    for (int k = 0; k < extraCount; ++k)
      if (extraTypes[k] == EXTRASAMPLE_ASSOCALPHA || extraTypes[k] == EXTRASAMPLE_UNASSALPHA) {
        layout.alphaChannel = layout.channels - extraCount + k;
        break;
      }
  return layout;
}

// Whether the samples can be read as the file stores them; the rest goes through libtiff's RGBA interface.
bool readsDirectly(const Layout& layout) {
  const bool photometric = layout.photometric == PHOTOMETRIC_MINISBLACK ||
                           layout.photometric == PHOTOMETRIC_MINISWHITE || layout.photometric == PHOTOMETRIC_RGB;
  const bool integer = (layout.format == SAMPLEFORMAT_UINT || layout.format == SAMPLEFORMAT_INT) &&
                       (layout.bits == 8 || layout.bits == 16 || layout.bits == 32);
  const bool floating =
      layout.format == SAMPLEFORMAT_IEEEFP && (layout.bits == 16 || layout.bits == 32 || layout.bits == 64);
  return photometric && (integer || floating);
}

bool keepsCodes(const Layout& layout) {
  return layout.format == SAMPLEFORMAT_UINT && (layout.bits == 8 || layout.bits == 16);
}

// One plane (all samples of an interleaved file, or one channel of a planar one) into `target`,
// rows of `width * pixelBytes` bytes.
bool readPlane(TIFF* tiff, const Layout& layout, std::uint16_t plane, std::size_t pixelBytes, unsigned char* target) {
  const std::size_t rowBytes = layout.width * pixelBytes;
  if (TIFFIsTiled(tiff)) {
    std::uint32_t tileWidth = 0, tileHeight = 0;
    TIFFGetField(tiff, TIFFTAG_TILEWIDTH, &tileWidth);
    TIFFGetField(tiff, TIFFTAG_TILELENGTH, &tileHeight);
    const tmsize_t tileBytes = TIFFTileSize(tiff);
    if (tileWidth == 0 || tileHeight == 0 || tileBytes <= 0 ||
        std::size_t(tileBytes) < std::size_t(tileWidth) * tileHeight * pixelBytes)
      return false;
    std::vector<unsigned char> tile(tileBytes);
    for (std::uint32_t y = 0; y < layout.height; y += tileHeight)
      for (std::uint32_t x = 0; x < layout.width; x += tileWidth) {
        if (TIFFReadTile(tiff, tile.data(), x, y, 0, plane) != tileBytes) return false;
        const std::uint32_t rows = std::min(tileHeight, layout.height - y),
                            columns = std::min(tileWidth, layout.width - x);
        for (std::uint32_t r = 0; r < rows; ++r)
          std::memcpy(target + (std::size_t(y + r) * layout.width + x) * pixelBytes,
                      tile.data() + std::size_t(r) * tileWidth * pixelBytes, columns * pixelBytes);
      }
    return true;
  }
  std::uint32_t rowsPerStrip = 0;
  TIFFGetFieldDefaulted(tiff, TIFFTAG_ROWSPERSTRIP, &rowsPerStrip);
  rowsPerStrip = std::clamp<std::uint32_t>(rowsPerStrip, 1, layout.height);
  for (std::uint32_t y = 0; y < layout.height; y += rowsPerStrip) {
    const tmsize_t bytes = tmsize_t(std::min(rowsPerStrip, layout.height - y) * rowBytes);
    if (TIFFReadEncodedStrip(tiff, TIFFComputeStrip(tiff, y, plane), target + y * rowBytes, bytes) != bytes)
      return false;
  }
  return true;
}

float floatFromHalf(std::uint16_t half) {
  const std::uint32_t sign = std::uint32_t(half & 0x8000) << 16, exponent = (half >> 10) & 0x1f,
                      mantissa = half & 0x3ff;
  if (exponent == 0) return (sign ? -1.0f : 1.0f) * std::ldexp(float(mantissa), -24);  // zero and subnormals
  std::uint32_t bits =
      sign | (exponent == 31 ? 0x7f800000u | (mantissa << 13) : ((exponent + 112) << 23) | (mantissa << 13));
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

// The file's samples (`count` of them) to Float32: wider integers scaled to [0, 1] (unsigned) or [-1, 1] (signed).
std::vector<unsigned char> floatsFromSamples(const std::vector<unsigned char>& file, const Layout& layout,
                                             std::size_t count) {
  std::vector<unsigned char> out(count * sizeof(float));
  auto* values = reinterpret_cast<float*>(out.data());
  const auto each = [&]<class T>(T, double scale, double lowest) {
    const T* samples = reinterpret_cast<const T*>(file.data());
    for (std::size_t i = 0; i < count; ++i) values[i] = float(std::max(double(samples[i]) / scale, lowest));
  };
  if (layout.format == SAMPLEFORMAT_IEEEFP) {
    if (layout.bits == 32) std::memcpy(values, file.data(), out.size());
    if (layout.bits == 64) each(double(), 1.0, -HUGE_VAL);
    if (layout.bits == 16)
      for (std::size_t i = 0; i < count; ++i)
        values[i] = floatFromHalf(reinterpret_cast<const std::uint16_t*>(file.data())[i]);
  } else if (layout.format == SAMPLEFORMAT_INT) {
    if (layout.bits == 8) each(std::int8_t(), 127.0, -1.0);
    if (layout.bits == 16) each(std::int16_t(), 32767.0, -1.0);
    if (layout.bits == 32) each(std::int32_t(), 2147483647.0, -1.0);
  } else {
    each(std::uint32_t(), 4294967295.0, 0.0);
  }
  return out;
}

// Grey stored with white as zero becomes grey with black as zero.
void invertCodes(std::vector<unsigned char>& file, const Layout& layout) {
  if (layout.bits == 8)
    for (auto& code : file) code = 255 - code;
  else
    for (auto& code : std::span(reinterpret_cast<std::uint16_t*>(file.data()), file.size() / 2)) code = 65535 - code;
}

Status readDirectly(TIFF* tiff, const fs::path& path, const Layout& layout, InterleavedCodes& out,
                    const std::string& messages) {
  const std::size_t bytes = layout.bits / 8, pixels = std::size_t(layout.width) * layout.height;
  std::vector<unsigned char> file(pixels * layout.channels * bytes);
  if (!layout.separatePlanes) {
    if (!readPlane(tiff, layout, 0, layout.channels * bytes, file.data()))
      return fileError(ErrorCode::Format, path, "cannot read pixels: " + reasonOr(messages, "damaged image data"));
  } else {
    std::vector<unsigned char> plane(pixels * bytes);
    for (std::uint16_t c = 0; c < layout.channels; ++c) {
      if (!readPlane(tiff, layout, c, bytes, plane.data()))
        return fileError(ErrorCode::Format, path, "cannot read pixels: " + reasonOr(messages, "damaged image data"));
      for (std::size_t i = 0; i < pixels; ++i)
        std::memcpy(&file[(i * layout.channels + c) * bytes], &plane[i * bytes], bytes);
    }
  }
  if (keepsCodes(layout)) {
    if (layout.photometric == PHOTOMETRIC_MINISWHITE) invertCodes(file, layout);
    out.samples = std::move(file);
  } else {
    out.samples = floatsFromSamples(file, layout, pixels * layout.channels);
  }
  return {};
}

// Palette, YCbCr, CMYK, bit depths below 8: libtiff's RGBA rendering, kept as grey or RGB (plus alpha).
Status readThroughRgba(TIFF* tiff, const fs::path& path, InterleavedCodes& out, const std::string& messages) {
  const std::size_t pixels = std::size_t(out.width) * out.height;
  std::vector<std::uint32_t> rgba(pixels);
  if (!TIFFReadRGBAImageOriented(tiff, out.width, out.height, rgba.data(), ORIENTATION_TOPLEFT, 0))
    return fileError(ErrorCode::Format, path, "cannot read pixels: " + reasonOr(messages, "damaged image data"));
  const int colors = out.channels - (out.alphaChannel >= 0 ? 1 : 0);
  out.samples.resize(pixels * out.channels);
  for (std::size_t i = 0; i < pixels; ++i) {
    unsigned char* pixel = &out.samples[i * out.channels];
    for (int c = 0; c < colors; ++c) pixel[c] = (unsigned char)(colors == 1 ? TIFFGetR(rgba[i]) : rgba[i] >> (8 * c));
    if (out.alphaChannel >= 0) pixel[colors] = (unsigned char)TIFFGetA(rgba[i]);
  }
  return {};
}

template <class T>
std::optional<double> meanOf(const T* values, std::uint16_t count) {
  if (!values || count == 0) return std::nullopt;
  double sum = 0;
  for (std::uint16_t k = 0; k < count; ++k) sum += values[k];
  return sum / count;
}

// The current page, as readTiff reads the first; `messages` is what libtiff reported on `tiff`.
Result<InterleavedCodes> readPage(TIFF* tiff, const fs::path& path, bool pixels, const std::string& messages,
                                  const std::function<Status(const InterleavedCodes&)>& checkHeader) {
  const Layout layout = layoutOf(tiff);
  if (layout.width == 0 || layout.height == 0 || layout.channels == 0)
    return fileError(ErrorCode::Format, path, "not a readable image: no pixels");

  InterleavedCodes out;
  out.width = int(layout.width);
  out.height = int(layout.height);
  if (layout.width > std::uint32_t(INT32_MAX) || layout.height > std::uint32_t(INT32_MAX))
    return fileError(ErrorCode::Format, path, "not a readable image: impossible size");
  const bool direct = readsDirectly(layout);
  char rgbaProblem[1024] = "";
  if (!direct && !TIFFRGBAImageOK(tiff, rgbaProblem))
    return fileError(ErrorCode::Unsupported, path, std::string("unsupported TIFF layout: ") + rgbaProblem);
  if (direct) {
    out.channels = layout.channels;
    out.type = !keepsCodes(layout) ? SampleType::Float32 : layout.bits == 8 ? SampleType::UInt8 : SampleType::UInt16;
    out.alphaChannel = layout.alphaChannel;
  } else {
    const bool grey = layout.photometric == PHOTOMETRIC_MINISBLACK || layout.photometric == PHOTOMETRIC_MINISWHITE;
    out.alphaChannel = layout.alphaChannel >= 0 ? (grey ? 1 : 3) : -1;
    out.channels = (grey ? 1 : 3) + (layout.alphaChannel >= 0 ? 1 : 0);
    out.type = SampleType::UInt8;
  }
  if (char* description = nullptr; TIFFGetField(tiff, TIFFTAG_IMAGEDESCRIPTION, &description) && description)
    out.description = description;
  LFCAM_TRY(checkHeader(out));
  if (!pixels) return out;
  LFCAM_TRY(direct ? readDirectly(tiff, path, layout, out, messages) : readThroughRgba(tiff, path, out, messages));
  return out;
}

Error notATiff(const fs::path& path, const std::string& messages) {
  return fileError(ErrorCode::Format, path, "not a readable TIFF: " + reasonOr(messages, "unknown error"));
}

// Whether `page` is laid out as `first`, the first page of its stack.
Status checkSameLayout(const fs::path& path, int z, const InterleavedCodes& page, const InterleavedCodes& first) {
  const auto describe = [](const InterleavedCodes& codes) {
    return std::to_string(codes.width) + "x" + std::to_string(codes.height) + " with " +
           std::to_string(codes.channels) + " channel(s) of " +
           (codes.type == SampleType::Float32  ? "float"
            : codes.type == SampleType::UInt16 ? "16-bit"
                                               : "8-bit") +
           " samples";
  };
  if (page.width == first.width && page.height == first.height && page.channels == first.channels &&
      page.type == first.type)
    return {};
  return fileError(ErrorCode::Format, path,
                   "pages differ: page " + std::to_string(z) + " is " + describe(page) + ", page 0 " + describe(first));
}

// Writes one page laid out as `layout` (its samples at `samples`), then closes its directory.
bool writePage(TIFF* t, const InterleavedCodes& layout, const std::string& description,
               const std::optional<TiffResolution>& resolution, const unsigned char* samples, std::size_t sampleBytes) {
  const std::size_t rowBytes = std::size_t(layout.width) * layout.channels * sampleBytes;
  const int colors = layout.channels >= 3 ? 3 : 1;
  std::vector<std::uint16_t> extra(layout.channels - colors, EXTRASAMPLE_UNSPECIFIED);
  if (layout.channels == 2 || layout.channels == 4) extra[0] = EXTRASAMPLE_UNASSALPHA;
  bool ok =
      TIFFSetField(t, TIFFTAG_IMAGEWIDTH, std::uint32_t(layout.width)) &&
      TIFFSetField(t, TIFFTAG_IMAGELENGTH, std::uint32_t(layout.height)) &&
      TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, std::uint16_t(layout.channels)) &&
      TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, std::uint16_t(8 * sampleBytes)) &&
      TIFFSetField(t, TIFFTAG_SAMPLEFORMAT,
                   std::uint16_t(layout.type == SampleType::Float32 ? SAMPLEFORMAT_IEEEFP : SAMPLEFORMAT_UINT)) &&
      TIFFSetField(t, TIFFTAG_PLANARCONFIG, std::uint16_t(PLANARCONFIG_CONTIG)) &&
      TIFFSetField(t, TIFFTAG_PHOTOMETRIC, std::uint16_t(colors == 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK)) &&
      TIFFSetField(t, TIFFTAG_COMPRESSION, std::uint16_t(COMPRESSION_ADOBE_DEFLATE)) &&
      TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, TIFFDefaultStripSize(t, 0));
  if (ok && !extra.empty()) ok = TIFFSetField(t, TIFFTAG_EXTRASAMPLES, std::uint16_t(extra.size()), extra.data());
  if (ok && !description.empty()) ok = TIFFSetField(t, TIFFTAG_IMAGEDESCRIPTION, description.c_str());
  if (ok && resolution)
    ok = TIFFSetField(t, TIFFTAG_XRESOLUTION, resolution->x) && TIFFSetField(t, TIFFTAG_YRESOLUTION, resolution->y) &&
         TIFFSetField(t, TIFFTAG_RESOLUTIONUNIT, resolution->unit);
  if (!ok) return false;
  std::vector<unsigned char> row(rowBytes);  // libtiff may encode in place
  for (int y = 0; y < layout.height; ++y) {
    std::memcpy(row.data(), samples + y * rowBytes, rowBytes);
    if (TIFFWriteScanline(t, row.data(), std::uint32_t(y), 0) < 0) return false;
  }
  return TIFFWriteDirectory(t);
}

}  // namespace

Result<InterleavedCodes> readTiff(const fs::path& path, bool pixels,
                                  const std::function<Status(const InterleavedCodes&)>& checkHeader) {
  std::string messages;
  const TiffHandle tiff = openTiff(path, "r", messages);
  if (!tiff) return notATiff(path, messages);
  return readPage(tiff.get(), path, pixels, messages, checkHeader);
}

Status readTiffStack(const fs::path& path, const std::function<Status(const TiffStack&)>& start,
                     const std::function<Status(int z, const InterleavedCodes& codes)>& page) {
  std::string messages;
  const TiffHandle tiff = openTiff(path, "r", messages);
  if (!tiff) return notATiff(path, messages);
  // Counting walks the whole chain of pages: a file cut short breaks it, and libtiff says so.
  const tdir_t pages = TIFFNumberOfDirectories(tiff.get());
  if (!messages.empty() || pages == 0 || pages > tdir_t(INT32_MAX))
    return fileError(ErrorCode::Format, path, "truncated or corrupt: " + reasonOr(messages, "no readable pages"));
  TiffStack stack;
  stack.pages = int(pages);
  const auto anyHeader = [](const InterleavedCodes&) { return Status(); };
  LFCAM_ASSIGN_OR_RETURN(stack.header, readPage(tiff.get(), path, false, messages, anyHeader));
  float x = 0, y = 0;
  std::uint16_t unit = RESUNIT_INCH;
  if (TIFFGetField(tiff.get(), TIFFTAG_XRESOLUTION, &x) && TIFFGetField(tiff.get(), TIFFTAG_YRESOLUTION, &y) &&
      TIFFGetFieldDefaulted(tiff.get(), TIFFTAG_RESOLUTIONUNIT, &unit))
    stack.resolution = TiffResolution{x, y, unit};
  LFCAM_TRY(start(stack));
  for (int z = 0; z < stack.pages; ++z) {
    if (z > 0 && !TIFFReadDirectory(tiff.get()))
      return fileError(ErrorCode::Format, path,
                       "cannot read page " + std::to_string(z) + ": " + reasonOr(messages, "damaged directory"));
    LFCAM_ASSIGN_OR_RETURN(auto codes, readPage(tiff.get(), path, true, messages, [&](const InterleavedCodes& header) {
                             return checkSameLayout(path, z, header, stack.header);
                           }));
    LFCAM_TRY(page(z, codes));
  }
  return {};
}

Status writeTiff(const fs::path& temporary, const fs::path& path, const InterleavedCodes& image) {
  const TiffStack stack{.header = {image.width, image.height, image.channels, image.type, {}, image.description},
                        .pages = 1};
  return writeTiffStack(temporary, path, stack, [&](int) { return image.samples.data(); });
}

Status writeTiffStack(const fs::path& temporary, const fs::path& path, const TiffStack& stack,
                      const std::function<const unsigned char*(int z)>& samples) {
  const InterleavedCodes& layout = stack.header;
  const std::size_t sampleBytes = layout.type == SampleType::UInt8 ? 1 : layout.type == SampleType::UInt16 ? 2 : 4;
  const std::size_t pageBytes = std::size_t(layout.width) * layout.height * layout.channels * sampleBytes;
  // Classic TIFF addresses 4 GiB; larger files go to BigTIFF.
  const bool big = pageBytes * stack.pages > (std::size_t(1) << 32) - (std::size_t(1) << 26);
  std::string messages;
  const TiffHandle tiff = openTiff(temporary, big ? "w8" : "w", messages);
  const auto failed = [&] {
    return fileError(ErrorCode::Io, path, "cannot write: " + reasonOr(messages, "unknown error"));
  };
  if (!tiff) return failed();
  for (int z = 0; z < stack.pages; ++z)
    if (!writePage(tiff.get(), layout, z == 0 ? layout.description : std::string(), stack.resolution, samples(z),
                   sampleBytes))
      return failed();
  return {};
}

TiffLevels readTiffLevels(const fs::path& path) {
  std::string messages;
  const TiffHandle tiff = openTiff(path, "r", messages);
  TiffLevels levels;
  if (!tiff) return levels;
  std::uint16_t count = 0;
  float* black = nullptr;  // libtiff's type for the tag, whatever the file stores (SHORT, LONG, RATIONAL)
  if (TIFFGetField(tiff.get(), TIFFTAG_BLACKLEVEL, &count, &black)) levels.black = meanOf(black, count);
  std::uint32_t* white = nullptr;
  if (TIFFGetField(tiff.get(), TIFFTAG_WHITELEVEL, &count, &white)) levels.white = meanOf(white, count);
  return levels;
}

}  // namespace lfcam::io
