#include "lfcam/core/sensor_layout.hpp"

namespace lfcam {

const char* packingName(Packing packing) { return packing == Packing::Square ? "square" : "hexagonal"; }

const char* colorFilterName(ColorFilter filter) {
  switch (filter) {
    case ColorFilter::RGGB: return "RGGB";
    case ColorFilter::BGGR: return "BGGR";
    case ColorFilter::GRBG: return "GRBG";
    case ColorFilter::GBRG: return "GBRG";
    case ColorFilter::Mono: return "mono";
  }
  return "?";
}

int colorFilterChannel(ColorFilter filter, int x, int y) {
  const int phase = (y & 1) * 2 + (x & 1);  // 0 top-left, 1 top-right, 2 bottom-left, 3 bottom-right
  switch (filter) {
    case ColorFilter::RGGB: {
      static const int c[4] = {0, 1, 1, 2};
      return c[phase];
    }
    case ColorFilter::BGGR: {
      static const int c[4] = {2, 1, 1, 0};
      return c[phase];
    }
    case ColorFilter::GRBG: {
      static const int c[4] = {1, 0, 2, 1};
      return c[phase];
    }
    case ColorFilter::GBRG: {
      static const int c[4] = {1, 2, 0, 1};
      return c[phase];
    }
    case ColorFilter::Mono: return -1;
  }
  return -1;
}

}  // namespace lfcam
