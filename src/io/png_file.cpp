#include "io/png_file.hpp"

#include <png.h>

#include <bit>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>

#include "io/io_support.hpp"
#include "io/png_check.hpp"

namespace lfcam::io {

namespace fs = std::filesystem;

namespace {

constexpr const char* kDescriptionKey = "Description";  // where OpenImageIO kept ImageDescription

// libpng reports errors by calling this and expects it not to return: the message is kept for the
// caller and control goes back to the setjmp of the function that started the work.
struct ErrorSink {
  char message[256] = "unknown error";
};

[[noreturn]] void onError(png_structp png, png_const_charp message) {
  auto* sink = static_cast<ErrorSink*>(png_get_error_ptr(png));
  std::snprintf(sink->message, sizeof sink->message, "%s", message);
  png_longjmp(png, 1);
}

void onWarning(png_structp, png_const_charp) {}  // benign (e.g. an unknown chunk); libpng would print it

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

std::string descriptionOf(png_structp png, png_infop info) {
  png_textp texts = nullptr;
  const int count = png_get_text(png, info, &texts, nullptr);
  for (int i = 0; i < count; ++i)
    if (std::strcmp(texts[i].key, kDescriptionKey) == 0) return std::string(texts[i].text, texts[i].text_length);
  return {};
}

// The expansions that leave 8-bit or 16-bit grey, grey+alpha, RGB or RGBA, in native byte order.
void requestPlainSamples(png_structp png, png_infop info) {
  const int colour = png_get_color_type(png, info), depth = png_get_bit_depth(png, info);
  if (colour == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (colour == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
  if (depth == 16 && std::endian::native == std::endian::little) png_set_swap(png);
  png_set_interlace_handling(png);
}

// The libpng part of reading, with only trivially destructible locals between setjmp and longjmp.
// Returns false with sink.message set on failure.
bool decode(std::FILE* file, ErrorSink& sink, InterleavedCodes& out, bool pixels,
            const std::function<Status(const InterleavedCodes&)>& checkHeader, Status& refused) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &sink, onError, onWarning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  png_bytep* volatile rows = nullptr;  // volatile: read after a longjmp
  if (!info || setjmp(png_jmpbuf(png))) {
    delete[] rows;
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_init_io(png, file);
  // checkPngStructure has verified every chunk's CRC, which also covers the deflate stream that
  // zlib's Adler-32 would check again: both are skipped here.
  png_set_crc_action(png, PNG_CRC_QUIET_USE, PNG_CRC_QUIET_USE);
  png_set_option(png, PNG_IGNORE_ADLER32, PNG_OPTION_ON);
  png_read_info(png, info);
  requestPlainSamples(png, info);
  png_read_update_info(png, info);
  out.width = int(png_get_image_width(png, info));
  out.height = int(png_get_image_height(png, info));
  out.channels = png_get_channels(png, info);
  out.type = png_get_bit_depth(png, info) == 16 ? SampleType::UInt16 : SampleType::UInt8;
  out.description = descriptionOf(png, info);
  refused = checkHeader(out);
  if (pixels && refused.ok()) {
    const std::size_t rowBytes = png_get_rowbytes(png, info);
    out.samples.resize(rowBytes * std::size_t(out.height));
    rows = new png_bytep[std::size_t(out.height)];
    for (int y = 0; y < out.height; ++y) rows[y] = out.samples.data() + rowBytes * std::size_t(y);
    png_read_image(png, rows);
    png_read_end(png, info);
    if (out.description.empty()) out.description = descriptionOf(png, info);  // text after the image data
  }
  delete[] rows;
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

// Where encoded bytes go: a FILE or a string.
struct Sink {
  std::FILE* file = nullptr;
  std::string* bytes = nullptr;
  bool failed = false;
};

void writeBytes(png_structp png, png_bytep data, png_size_t length) {
  auto* sink = static_cast<Sink*>(png_get_io_ptr(png));
  if (sink->bytes)
    sink->bytes->append(reinterpret_cast<const char*>(data), length);
  else if (std::fwrite(data, 1, length, sink->file) != length)
    sink->failed = true;
}

void flushBytes(png_structp) {}

bool encode(const InterleavedCodes& image, Sink& sink, ErrorSink& errors) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &errors, onError, onWarning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  png_bytep* volatile rows = nullptr;  // volatile: read after a longjmp
  if (!info || setjmp(png_jmpbuf(png))) {
    delete[] rows;
    png_destroy_write_struct(&png, &info);
    return false;
  }
  static constexpr int kColorTypes[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                        PNG_COLOR_TYPE_RGB_ALPHA};
  const bool sixteen = image.type == SampleType::UInt16;
  png_set_write_fn(png, &sink, writeBytes, flushBytes);
  // Speed first: the outputs are mostly intermediate (stacks, views, the viewer's answers). zlib level 1
  // and the Up filter alone instead of libpng's per-row trial of all five (docs/design.md, "Start-up").
  png_set_compression_level(png, 1);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_UP);
  png_set_IHDR(png, info, png_uint_32(image.width), png_uint_32(image.height), sixteen ? 16 : 8,
               kColorTypes[image.channels - 1], PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  // 8-bit codes are sRGB; 16-bit codes are linear (image_io.hpp).
  if (sixteen)
    png_set_gAMA_fixed(png, info, PNG_GAMMA_LINEAR);
  else
    png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_text text{};
  if (!image.description.empty()) {
    text.compression = PNG_TEXT_COMPRESSION_NONE;
    text.key = const_cast<char*>(kDescriptionKey);
    text.text = const_cast<char*>(image.description.c_str());
    text.text_length = image.description.size();
    png_set_text(png, info, &text, 1);
  }
  png_write_info(png, info);
  if (sixteen && std::endian::native == std::endian::little) png_set_swap(png);
  const std::size_t rowBytes = std::size_t(image.width) * image.channels * (sixteen ? 2 : 1);
  rows = new png_bytep[std::size_t(image.height)];
  for (int y = 0; y < image.height; ++y)
    rows[y] = const_cast<png_bytep>(image.samples.data()) + rowBytes * std::size_t(y);
  png_write_image(png, rows);
  png_write_end(png, info);
  delete[] rows;
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

Result<InterleavedCodes> readPng(const fs::path& path, bool pixels,
                                 const std::function<Status(const InterleavedCodes&)>& checkHeader) {
  LFCAM_TRY(checkPngStructure(path, pixels));
  File file(std::fopen(path.c_str(), "rb"));
  if (!file) return fileError(ErrorCode::Io, path, "cannot open: " + std::string(std::strerror(errno)));
  ErrorSink errors;
  InterleavedCodes out;
  Status refused;
  if (!decode(file.get(), errors, out, pixels, checkHeader, refused))
    return fileError(ErrorCode::Format, path, std::string("cannot read pixels: ") + errors.message);
  if (!refused.ok()) return refused.error();
  return out;
}

Status writePng(const fs::path& temporary, const fs::path& path, const InterleavedCodes& image) {
  File file(std::fopen(temporary.c_str(), "wb"));
  if (!file) return fileError(ErrorCode::Io, path, "cannot write: " + std::string(std::strerror(errno)));
  Sink sink{.file = file.get()};
  ErrorSink errors;
  if (!encode(image, sink, errors))
    return fileError(ErrorCode::Io, path, std::string("cannot write: ") + errors.message);
  if (sink.failed || std::fflush(file.get()) != 0)
    return fileError(ErrorCode::Io, path, "cannot write: " + std::string(std::strerror(errno)));
  return {};
}

Result<std::string> encodePng(const InterleavedCodes& image) {
  std::string bytes;
  Sink sink{.bytes = &bytes};
  ErrorSink errors;
  if (!encode(image, sink, errors)) return makeError(ErrorCode::Io, std::string("encodePng: ") + errors.message);
  return bytes;
}

}  // namespace lfcam::io
