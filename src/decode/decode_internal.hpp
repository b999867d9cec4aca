// Pieces shared by the decoder's files (not public).
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "lfcam/calibrate/lenslet_grid.hpp"
#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/core/sensor_layout.hpp"
#include "lfcam/decode/decode.hpp"
#include "lfcam/raw_io/raw_image.hpp"

namespace lfcam::decode_detail {

// The fast kernels, or the plain per-pixel and per-sample ones they are tested against (slow).
enum class Kernels { Fast, Reference };

// decodeLightField (decode.hpp) with the chosen kernels.
Result<LightField> decodeLightField(const RawImage& raw, const LensletGrid& grid, const DecodeOptions& options,
                                    Kernels kernels);

// Plain per-pixel implementations of demosaic (decode.hpp), the references the fast kernels are
// tested against (LightFieldAware's with bounds-checked taps everywhere; LensletAware has only one).
Image demosaicReference(const Image& mosaic, ColorFilter filter, DemosaicMethod method,
                        const LensletGrid* grid = nullptr);

// Colour (0 R, 1 G, 2 B) of photosite (x, y) of a Bayer filter, from a 2x2 table.
struct CfaTable {
  explicit CfaTable(ColorFilter filter);
  int operator()(int x, int y) const { return phase[(y & 1) * 2 + (x & 1)]; }
  std::array<int, 4> phase{};
};

// Reflect-101 border: index -1 -> 1, n -> n - 2. Keeps the Bayer parity of every index.
inline int reflect(int i, int n) {
  if (n == 1) return 0;
  while (i < 0 || i >= n) i = i < 0 ? -i : 2 * (n - 1) - i;
  return i;
}

// Reads a mosaic with reflected borders.
struct Mosaic {
  const float* data;
  int width, height;
  float operator()(int x, int y) const { return data[std::size_t(reflect(y, height)) * width + reflect(x, width)]; }
};

// Direct access, for pixels at least 2 from every border.
struct Direct {
  const float* data;
  int width;
  float operator()(int x, int y) const { return data[std::size_t(y) * width + x]; }
};

// Malvar-He-Cutler's green at a red or blue photosite (x, y), any accessor `m` (reflected or direct).
template <class M>
inline float mhcGreenAtRB(const M& m, int x, int y) {
  return (4 * m(x, y) + 2 * (m(x, y - 1) + m(x, y + 1) + m(x - 1, y) + m(x + 1, y)) -
          (m(x, y - 2) + m(x, y + 2) + m(x - 2, y) + m(x + 2, y))) *
         0.125f;
}

// Hamilton-Adams's green at a red or blue photosite: the direction (across or down) with the
// smaller gradient and Laplacian, corrected by the centre colour's Laplacian along it.
template <class M>
inline float haGreen(const M& m, int x, int y) {
  const float c = m(x, y);
  const float lapH = 2 * c - m(x - 2, y) - m(x + 2, y), lapV = 2 * c - m(x, y - 2) - m(x, y + 2);
  const float dH = std::abs(m(x - 1, y) - m(x + 1, y)) + std::abs(lapH);
  const float dV = std::abs(m(x, y - 1) - m(x, y + 1)) + std::abs(lapV);
  const float gH = 0.5f * (m(x - 1, y) + m(x + 1, y)) + 0.25f * lapH;
  const float gV = 0.5f * (m(x, y - 1) + m(x, y + 1)) + 0.25f * lapV;
  return dH < dV ? gH : dV < dH ? gV : 0.5f * (gH + gV);
}

// DemosaicMethod::LightFieldAware (demosaic_light_field.cpp) of a Bayer mosaic. `weight`: how lit
// each photosite is (devignetting's weight, 0 between microlens images; empty: all lit).
// `reference`: the plain bounds-checked taps everywhere, what the fast ones are tested against.
Image demosaicLightField(const Image& mosaic, ColorFilter filter, const LensletGrid& grid, const Image& weight,
                         bool reference = false);

// For every pixel, a number naming the microlens whose centre is nearest (its Voronoi cell).
std::vector<int> microlensLabels(const LensletGrid& grid, int width, int height);

// What the sampler needs to know about the views.
struct ViewLayout {
  int views = 1;
  Sampling sampling = Sampling::SubPixel;
  // Sensor pixels from one view to the next along the lattice's axes: IntegralPitch's pitch /
  // round(pitch), Bricks' pitchX / views and pitchY / views (SubPixel's: one, along the raw's axes).
  std::array<double, 2> step{1, 1};
  int firstRow = 0;  // the light field's row t is the grid's row t + firstRow
};

// Fills lf (views x views, grid.columns x (grid.rows - firstRow), planes.channels() channels, weight enabled)
// by sampling `planes` (and `weight`, one plane, when not empty) under every microlens, in the
// orientation of decode.hpp. Without `weight`, samples get weight 1 (0 off the sensor).
// `reference`: one sample at a time, the plain version the fast kernel is tested against.
void sampleLenslets(const Image& planes, const Image& weight, const LensletGrid& grid, const ViewLayout& layout,
                    LightField& lf, bool reference);

// decodeLightField's steps before and after demosaicing (decode.cpp), apart so that a test can
// decode a full-colour mosaic it knows (the simulator's true colour at every photosite: a perfect
// demosaic) exactly as the decoder decodes a demosaiced one.
struct Devignetted {
  Image value;   // offset and scaled, hot pixels repaired, over the white image (unlit ones filled)
  Image weight;  // devignetting's weight per photosite; empty without a white image
};
// Steps 1 and 2, after checking the inputs.
Result<Devignetted> devignettedMosaic(const RawImage& raw, const LensletGrid& grid, const DecodeOptions& options);
// Steps 4 to 6: `planes` (3, or 1 for a Mono raw, of the raw's size) and `weight` as step 2 left them.
Result<LightField> decodeDemosaiced(Image planes, Image weight, const RawImage& raw, const LensletGrid& grid,
                                    const DecodeOptions& options, Kernels kernels = Kernels::Fast);

}  // namespace lfcam::decode_detail
