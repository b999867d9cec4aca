// An image file's samples as the file holds them: interleaved 8-bit or 16-bit (native byte
// order) codes, or floats (TIFF), with the file's description text. The readers and writers that
// go through the formats' own libraries (io/png_file, io/jpeg_file, io/tiff_file) exchange this;
// image_io converts to and from linear planes.
#pragma once

#include <string>
#include <vector>

#include "lfcam/io/image_io.hpp"

namespace lfcam::io {

struct InterleavedCodes {
  int width = 0, height = 0, channels = 0;
  SampleType type = SampleType::UInt8;
  std::vector<unsigned char> samples;  // empty when only the header was read
  std::string description;             // the file's description field, if any
  int alphaChannel = -1;               // TIFF: the channel its extra-sample tag calls alpha, or -1
};

}  // namespace lfcam::io
