// Image files in memory: JPEG and PNG bytes for the viewer's answers and the living picture,
// through the same encoders as image_io.hpp, without a file.
// Values are linear light and are written sRGB-encoded, 8 bits, like writeImage does.
#pragma once

#include <string>

#include "lfcam/core/image.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam {

enum class EncodedFormat { Jpeg, Png };

struct EncodeOptions {
  EncodedFormat format = EncodedFormat::Jpeg;
  int jpegQuality = 85;  // 1..100
};

// The file's bytes. One or two channels are written grey (the first), three or more as RGB (the
// first three: a light field's extra channels are not shown). Usage error for an empty image.
Result<std::string> encodeImage(const Image& image, const EncodeOptions& options = {});

// Standard base64 (RFC 4648, with padding), for data: URLs.
std::string base64Encode(const std::string& bytes);

}  // namespace lfcam
