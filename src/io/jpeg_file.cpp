#include "io/jpeg_file.hpp"

// jpeglib.h needs size_t and FILE declared first.
#include <jpeglib.h>
#include <cstdio>

#include <algorithm>
#include <csetjmp>
#include <cstdlib>
#include <cstring>
#include <memory>

#include "io/io_support.hpp"

namespace lfcam::io {

namespace fs = std::filesystem;

namespace {

// libjpeg reports errors by calling error_exit, which must not return: the message is kept and
// control goes back to the setjmp of the function that started the work. Warnings (corrupt data
// libjpeg can skip) are kept too: a damaged file is an error for lfcam, not a silently grey one.
struct ErrorManager {
  jpeg_error_mgr base;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX] = "unknown error";
  bool warned = false;
};

[[noreturn]] void onError(j_common_ptr info) {
  auto* errors = reinterpret_cast<ErrorManager*>(info->err);
  info->err->format_message(info, errors->message);
  std::longjmp(errors->jump, 1);
}

void onMessage(j_common_ptr info, int level) {
  auto* errors = reinterpret_cast<ErrorManager*>(info->err);
  if (level < 0 && !errors->warned) {
    info->err->format_message(info, errors->message);
    errors->warned = true;
  }
}

void useErrorManager(ErrorManager& errors) {
  jpeg_std_error(&errors.base);
  errors.base.error_exit = onError;
  errors.base.emit_message = onMessage;
}

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

std::string commentOf(const jpeg_decompress_struct& info) {
  for (jpeg_saved_marker_ptr marker = info.marker_list; marker; marker = marker->next)
    if (marker->marker == JPEG_COM)
      return std::string(reinterpret_cast<const char*>(marker->data), marker->data_length);
  return {};
}

// CMYK as Adobe applications store it (inverted) to RGB.
void rgbFromCmyk(const unsigned char* cmyk, unsigned char* rgb, int width) {
  for (int x = 0; x < width; ++x, cmyk += 4, rgb += 3)
    for (int c = 0; c < 3; ++c) rgb[c] = (unsigned char)((cmyk[c] * cmyk[3] + 127) / 255);
}

// The libjpeg part of reading, with only trivially destructible locals between setjmp and longjmp.
bool decode(std::FILE* file, ErrorManager& errors, InterleavedCodes& out, bool pixels,
            const std::function<Status(const InterleavedCodes&)>& checkHeader, Status& refused) {
  jpeg_decompress_struct info;
  info.err = &errors.base;
  unsigned char* volatile cmykRow = nullptr;  // volatile: read after a longjmp
  if (setjmp(errors.jump)) {
    std::free(cmykRow);
    jpeg_destroy_decompress(&info);
    return false;
  }
  jpeg_create_decompress(&info);
  jpeg_stdio_src(&info, file);
  jpeg_save_markers(&info, JPEG_COM, 0xffff);
  jpeg_read_header(&info, TRUE);
  const bool cmyk = info.jpeg_color_space == JCS_CMYK || info.jpeg_color_space == JCS_YCCK;
  info.out_color_space = info.num_components == 1 ? JCS_GRAYSCALE : cmyk ? JCS_CMYK : JCS_RGB;
  out.width = int(info.image_width);
  out.height = int(info.image_height);
  out.channels = info.num_components == 1 ? 1 : 3;
  out.type = SampleType::UInt8;
  out.description = commentOf(info);
  refused = checkHeader(out);
  if (pixels && refused.ok()) {
    jpeg_start_decompress(&info);
    const std::size_t rowBytes = std::size_t(out.width) * out.channels;
    out.samples.resize(rowBytes * std::size_t(out.height));
    if (cmyk) cmykRow = static_cast<unsigned char*>(std::malloc(std::size_t(out.width) * 4));
    while (info.output_scanline < info.output_height) {
      unsigned char* row = out.samples.data() + rowBytes * info.output_scanline;
      JSAMPROW target = cmyk ? cmykRow : row;
      jpeg_read_scanlines(&info, &target, 1);
      if (cmyk) rgbFromCmyk(cmykRow, row, out.width);
    }
    jpeg_finish_decompress(&info);
  }
  std::free(cmykRow);
  jpeg_destroy_decompress(&info);
  return !errors.warned;
}

// Encodes to a FILE, or to memory when `file` is null (`*bytes`, `*length`: freed by the caller).
bool encode(const InterleavedCodes& image, int quality, std::FILE* file, unsigned char** bytes, unsigned long* length,
            ErrorManager& errors) {
  jpeg_compress_struct info;
  info.err = &errors.base;
  if (setjmp(errors.jump)) {
    jpeg_destroy_compress(&info);
    return false;
  }
  jpeg_create_compress(&info);
  if (file)
    jpeg_stdio_dest(&info, file);
  else
    jpeg_mem_dest(&info, bytes, length);
  info.image_width = JDIMENSION(image.width);
  info.image_height = JDIMENSION(image.height);
  info.input_components = image.channels;
  info.in_color_space = image.channels == 1 ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_set_defaults(&info);
  jpeg_set_quality(&info, quality, TRUE);
  jpeg_start_compress(&info, TRUE);
  if (!image.description.empty())
    jpeg_write_marker(&info, JPEG_COM, reinterpret_cast<const JOCTET*>(image.description.data()),
                      unsigned(std::min<std::size_t>(image.description.size(), 65533)));
  const std::size_t rowBytes = std::size_t(image.width) * image.channels;
  while (info.next_scanline < info.image_height) {
    JSAMPROW row = const_cast<JSAMPROW>(image.samples.data() + rowBytes * info.next_scanline);
    jpeg_write_scanlines(&info, &row, 1);
  }
  jpeg_finish_compress(&info);
  jpeg_destroy_compress(&info);
  return true;
}

}  // namespace

Result<InterleavedCodes> readJpeg(const fs::path& path, bool pixels,
                                  const std::function<Status(const InterleavedCodes&)>& checkHeader) {
  File file(std::fopen(path.c_str(), "rb"));
  if (!file) return fileError(ErrorCode::Io, path, "cannot open: " + std::string(std::strerror(errno)));
  ErrorManager errors;
  useErrorManager(errors);
  InterleavedCodes out;
  Status refused;
  if (!decode(file.get(), errors, out, pixels, checkHeader, refused))
    return fileError(ErrorCode::Format, path, std::string("not a readable JPEG: ") + errors.message);
  if (!refused.ok()) return refused.error();
  return out;
}

Status writeJpeg(const fs::path& temporary, const fs::path& path, const InterleavedCodes& image, int quality) {
  File file(std::fopen(temporary.c_str(), "wb"));
  if (!file) return fileError(ErrorCode::Io, path, "cannot write: " + std::string(std::strerror(errno)));
  ErrorManager errors;
  useErrorManager(errors);
  if (!encode(image, quality, file.get(), nullptr, nullptr, errors))
    return fileError(ErrorCode::Io, path, std::string("cannot write: ") + errors.message);
  if (std::ferror(file.get()) || std::fflush(file.get()) != 0)
    return fileError(ErrorCode::Io, path, "cannot write: " + std::string(std::strerror(errno)));
  return {};
}

Result<std::string> encodeJpeg(const InterleavedCodes& image, int quality) {
  ErrorManager errors;
  useErrorManager(errors);
  unsigned char* bytes = nullptr;
  unsigned long length = 0;
  const bool encoded = encode(image, quality, nullptr, &bytes, &length, errors);
  std::string out = encoded ? std::string(reinterpret_cast<const char*>(bytes), length) : std::string();
  std::free(bytes);
  if (!encoded) return makeError(ErrorCode::Io, std::string("encodeJpeg: ") + errors.message);
  return out;
}

}  // namespace lfcam::io
