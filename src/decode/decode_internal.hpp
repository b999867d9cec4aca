// Pieces shared by the decoder's files (not public).
#pragma once

#include <array>
#include <vector>

#include "lfcam/camera_model.hpp"
#include "lfcam/decode.hpp"
#include "lfcam/image.hpp"
#include "lfcam/lenslet_grid.hpp"
#include "lfcam/light_field.hpp"

namespace lfcam::decode_detail {

// Colour (0 R, 1 G, 2 B) of photosite (x, y) of a Bayer filter, from a 2x2 table.
struct CfaTable {
  explicit CfaTable(ColorFilter filter);
  int operator()(int x, int y) const { return phase[(y & 1) * 2 + (x & 1)]; }
  std::array<int, 4> phase{};
};

// For every pixel, a number naming the microlens whose centre is nearest (its Voronoi cell).
std::vector<int> microlensLabels(const LensletGrid& grid, int width, int height);

// What the sampler needs to know about the views.
struct ViewLayout {
  int views = 1;
  Sampling sampling = Sampling::SubPixel;
  double integralScale = 1;  // IntegralPitch: sensor pixels per resampled pixel (pitch / round(pitch))
};

// Fills lf (views x views, grid.columns x grid.rows, planes.channels() channels, weight enabled)
// by sampling `planes` (and `weight`, one plane, when not empty) under every microlens, in the
// orientation of decode.hpp. Without `weight`, samples get weight 1 (0 off the sensor).
// `reference`: one sample at a time, the plain version the fast kernel is tested against.
void sampleLenslets(const Image& planes, const Image& weight, const LensletGrid& grid, const ViewLayout& layout,
                    LightField& lf, bool reference);

}  // namespace lfcam::decode_detail
