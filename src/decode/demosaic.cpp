// Demosaicing of a Bayer mosaic: Malvar-He-Cutler, Hamilton-Adams and a lenslet-aware bilinear one
// (the light-field-aware one is in demosaic_light_field.cpp),
// each with a plain per-pixel reference (reflected borders) and a fast row-parallel kernel that
// skips the border checks inside the image. Also hot-pixel repair.
#include <algorithm>
#include <array>
#include <cmath>

#include "core/parallel.hpp"
#include "decode/decode_internal.hpp"
#include "lfcam/core/sensor_layout.hpp"
#include "lfcam/decode/decode.hpp"

namespace lfcam {

namespace {

using decode_detail::CfaTable;

using decode_detail::Direct;
using decode_detail::haGreen;
using decode_detail::mhcGreenAtRB;
using decode_detail::Mosaic;

// ---- Malvar-He-Cutler (2004): bilinear corrected by the Laplacian of the centre colour.

// The kernels of the paper, at (x, y), any accessor `m` (reflected or direct); green at red and
// blue is in decode_internal.hpp (the light-field-aware demosaic uses it too).
// At a green pixel whose left and right neighbours have the wanted colour.
template <class M>
inline float mhcRowNeighbours(const M& m, int x, int y) {
  return (5 * m(x, y) + 4 * (m(x - 1, y) + m(x + 1, y)) - (m(x - 2, y) + m(x + 2, y)) -
          (m(x - 1, y - 1) + m(x + 1, y - 1) + m(x - 1, y + 1) + m(x + 1, y + 1)) +
          0.5f * (m(x, y - 2) + m(x, y + 2))) *
         0.125f;
}
// At a green pixel whose upper and lower neighbours have the wanted colour.
template <class M>
inline float mhcColumnNeighbours(const M& m, int x, int y) {
  return (5 * m(x, y) + 4 * (m(x, y - 1) + m(x, y + 1)) - (m(x, y - 2) + m(x, y + 2)) -
          (m(x - 1, y - 1) + m(x + 1, y - 1) + m(x - 1, y + 1) + m(x + 1, y + 1)) +
          0.5f * (m(x - 2, y) + m(x + 2, y))) *
         0.125f;
}
// Red at blue or blue at red: the diagonal neighbours.
template <class M>
inline float mhcDiagonal(const M& m, int x, int y) {
  return (6 * m(x, y) + 2 * (m(x - 1, y - 1) + m(x + 1, y - 1) + m(x - 1, y + 1) + m(x + 1, y + 1)) -
          1.5f * (m(x, y - 2) + m(x, y + 2) + m(x - 2, y) + m(x + 2, y))) *
         0.125f;
}

template <class M>
inline void mhcPixel(const M& m, const CfaTable& cfa, int x, int y, float out[3]) {
  const int c = cfa(x, y);
  out[c] = m(x, y);
  if (c == 1) {
    const int horizontal = cfa(x + 1, y);  // colour of the left/right neighbours
    out[horizontal] = mhcRowNeighbours(m, x, y);
    out[2 - horizontal] = mhcColumnNeighbours(m, x, y);
  } else {
    out[1] = mhcGreenAtRB(m, x, y);
    out[2 - c] = mhcDiagonal(m, x, y);
  }
}

// ---- Hamilton-Adams (1997): green interpolated along the smoother direction (gradient plus
// Laplacian of the centre colour; haGreen is in decode_internal.hpp), then red and blue from
// colour differences.

// Second pass: `m` the mosaic, `g` the full green plane (same accessor type).
template <class M>
inline void haPixel(const M& m, const M& g, const CfaTable& cfa, int x, int y, float out[3]) {
  const int c = cfa(x, y);
  const float green = g(x, y);
  out[1] = green;
  if (c == 1) {
    const int horizontal = cfa(x + 1, y);
    out[horizontal] = green + 0.5f * ((m(x - 1, y) - g(x - 1, y)) + (m(x + 1, y) - g(x + 1, y)));
    out[2 - horizontal] = green + 0.5f * ((m(x, y - 1) - g(x, y - 1)) + (m(x, y + 1) - g(x, y + 1)));
    return;
  }
  out[c] = m(x, y);
  // The other colour on the diagonals: along the one with the smaller gradient.
  const float d1 =
      std::abs(m(x - 1, y - 1) - m(x + 1, y + 1)) + std::abs(2 * green - g(x - 1, y - 1) - g(x + 1, y + 1));
  const float d2 =
      std::abs(m(x + 1, y - 1) - m(x - 1, y + 1)) + std::abs(2 * green - g(x + 1, y - 1) - g(x - 1, y + 1));
  const float e1 = 0.5f * ((m(x - 1, y - 1) - g(x - 1, y - 1)) + (m(x + 1, y + 1) - g(x + 1, y + 1)));
  const float e2 = 0.5f * ((m(x + 1, y - 1) - g(x + 1, y - 1)) + (m(x - 1, y + 1) - g(x - 1, y + 1)));
  out[2 - c] = green + (d1 < d2 ? e1 : d2 < d1 ? e2 : 0.5f * (e1 + e2));
}

Image monoCopy(const Image& mosaic) { return mosaic.copy(); }

// ---- Lenslet-aware: bilinear from the same-colour pixels of the same microlens only.

Image demosaicLensletAware(const Image& mosaic, const CfaTable& cfa, const LensletGrid& grid) {
  const int w = mosaic.width(), h = mosaic.height();
  const std::vector<int> label = decode_detail::microlensLabels(grid, w, h);
  Image out(w, h, 3);
  const Mosaic m{mosaic.plane(0), w, h};
  parallelFor(0, std::size_t(h), 8, [&](std::size_t begin, std::size_t end) {
    for (int y = int(begin); y < int(end); ++y)
      for (int x = 0; x < w; ++x) {
        const int own = label[std::size_t(y) * w + x];
        for (int c = 0; c < 3; ++c) {
          if (cfa(x, y) == c) {
            out.at(x, y, c) = m(x, y);
            continue;
          }
          // 3x3 first, then 5x5 if the cell edge leaves no pixel of colour c nearby; a sliver of
          // a cell at the image's edge may have none at all: then the neighbours of any cell.
          float value = m(x, y);
          for (int pass = 0; pass < 3; ++pass) {
            const int radius = pass == 0 ? 1 : 2;
            float sum = 0;
            int count = 0;
            for (int dy = -radius; dy <= radius; ++dy)
              for (int dx = -radius; dx <= radius; ++dx) {
                const int xx = x + dx, yy = y + dy;
                if (xx < 0 || yy < 0 || xx >= w || yy >= h || cfa(xx, yy) != c) continue;
                if (pass < 2 && label[std::size_t(yy) * w + xx] != own) continue;
                sum += m(xx, yy), ++count;
              }
            if (count > 0) {
              value = sum / count;
              break;
            }
          }
          out.at(x, y, c) = value;
        }
      }
  });
  return out;
}

}  // namespace

namespace decode_detail {

CfaTable::CfaTable(ColorFilter filter) {
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) phase[y * 2 + x] = colorFilterChannel(filter, x, y);
}

std::vector<int> microlensLabels(const LensletGrid& grid, int width, int height) {
  std::vector<int> label(std::size_t(width) * height);
  const double cs = std::cos(grid.rotationRad), sn = std::sin(grid.rotationRad);
  parallelFor(0, std::size_t(height), 16, [&](std::size_t begin, std::size_t end) {
    for (int y = int(begin); y < int(end); ++y)
      for (int x = 0; x < width; ++x) {
        // Lattice coordinates of the pixel centre, then the nearest centre among the rows around.
        const double dx = x + 0.5 - grid.origin[0], dy = y + 0.5 - grid.origin[1];
        const double a = (cs * dx + sn * dy) / grid.pitchX, b = (-sn * dx + cs * dy) / grid.pitchY;
        const int j0 = int(std::floor(b + 0.5));
        double best = 1e300;
        int bestLabel = -1;
        for (int j = j0 - 1; j <= j0 + 1; ++j) {
          const double shift = grid.packing == Packing::Hexagonal && ((j + grid.hexParity) & 1) ? 0.5 : 0.0;
          const int i = int(std::floor(a - shift + 0.5));
          const double ea = (a - shift - i) * grid.pitchX, eb = (b - j) * grid.pitchY;
          const double d = ea * ea + eb * eb;
          if (d < best) best = d, bestLabel = j * (grid.columns + 4) + i;  // unique per (i, j), also off-grid
        }
        label[std::size_t(y) * width + x] = bestLabel;
      }
  });
  return label;
}

Image demosaicReference(const Image& mosaic, ColorFilter filter, DemosaicMethod method, const LensletGrid* grid) {
  if (filter == ColorFilter::Mono) return monoCopy(mosaic);
  const CfaTable cfa(filter);
  if (method == DemosaicMethod::LensletAware && grid) return demosaicLensletAware(mosaic, cfa, *grid);
  if (method == DemosaicMethod::LightFieldAware && grid)
    return demosaicLightField(mosaic, filter, *grid, Image(), true);
  const int w = mosaic.width(), h = mosaic.height();
  Image out(w, h, 3);
  const Mosaic m{mosaic.plane(0), w, h};
  if (method == DemosaicMethod::HamiltonAdams) {
    Image green(w, h, 1);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) green.at(x, y, 0) = cfa(x, y) == 1 ? m(x, y) : haGreen(m, x, y);
    const Mosaic g{green.plane(0), w, h};
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        float rgb[3];
        haPixel(m, g, cfa, x, y, rgb);
        for (int c = 0; c < 3; ++c) out.at(x, y, c) = rgb[c];
      }
    return out;
  }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float rgb[3];
      mhcPixel(m, cfa, x, y, rgb);
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = rgb[c];
    }
  return out;
}

}  // namespace decode_detail

Image demosaic(const Image& mosaic, ColorFilter filter, DemosaicMethod method, const LensletGrid* grid) {
  if (filter == ColorFilter::Mono) return monoCopy(mosaic);
  const CfaTable cfa(filter);
  if (method == DemosaicMethod::LensletAware && grid) return demosaicLensletAware(mosaic, cfa, *grid);
  if (method == DemosaicMethod::LightFieldAware && grid)
    return decode_detail::demosaicLightField(mosaic, filter, *grid, Image());
  const int w = mosaic.width(), h = mosaic.height();
  if (w < 8 || h < 8) return decode_detail::demosaicReference(mosaic, filter, method);
  Image out(w, h, 3);
  const Mosaic reflected{mosaic.plane(0), w, h};
  const Direct direct{mosaic.plane(0), w};
  float* planes[3] = {out.plane(0), out.plane(1), out.plane(2)};
  auto isBorder = [&](int y) { return y < 2 || y >= h - 2; };

  // Runs `pixel(accessor..., x, y, rgb)` over rows [begin, end): direct access inside, reflected
  // at the borders.
  auto runRows = [&](std::size_t begin, std::size_t end, auto&& inside, auto&& border) {
    for (int y = int(begin); y < int(end); ++y) {
      const std::size_t rowStart = std::size_t(y) * w;
      float rgb[3];
      auto store = [&](int x) {
        for (int c = 0; c < 3; ++c) planes[c][rowStart + x] = rgb[c];
      };
      if (isBorder(y)) {
        for (int x = 0; x < w; ++x) border(x, y, rgb), store(x);
        continue;
      }
      for (int x = 0; x < 2; ++x) border(x, y, rgb), store(x);
      for (int x = 2; x < w - 2; ++x) inside(x, y, rgb), store(x);
      for (int x = w - 2; x < w; ++x) border(x, y, rgb), store(x);
    }
  };

  if (method == DemosaicMethod::HamiltonAdams) {
    Image green(w, h, 1);
    float* gp = green.plane(0);
    parallelFor(0, std::size_t(h), 16, [&](std::size_t begin, std::size_t end) {
      for (int y = int(begin); y < int(end); ++y) {
        const bool border = isBorder(y);
        for (int x = 0; x < w; ++x) {
          float value;
          if (cfa(x, y) == 1)
            value = direct(x, y);
          else if (border || x < 2 || x >= w - 2)
            value = haGreen(reflected, x, y);
          else
            value = haGreen(direct, x, y);
          gp[std::size_t(y) * w + x] = value;
        }
      }
    });
    const Mosaic gReflected{gp, w, h};
    const Direct gDirect{gp, w};
    parallelFor(0, std::size_t(h), 16, [&](std::size_t begin, std::size_t end) {
      runRows(
          begin, end, [&](int x, int y, float* rgb) { haPixel(direct, gDirect, cfa, x, y, rgb); },
          [&](int x, int y, float* rgb) { haPixel(reflected, gReflected, cfa, x, y, rgb); });
    });
    return out;
  }
  parallelFor(0, std::size_t(h), 16, [&](std::size_t begin, std::size_t end) {
    runRows(
        begin, end, [&](int x, int y, float* rgb) { mhcPixel(direct, cfa, x, y, rgb); },
        [&](int x, int y, float* rgb) { mhcPixel(reflected, cfa, x, y, rgb); });
  });
  return out;
}

int repairHotPixels(Image& mosaic, ColorFilter filter, float threshold) {
  const int w = mosaic.width(), h = mosaic.height();
  const int step = filter == ColorFilter::Mono ? 1 : 2;  // distance to the same-colour neighbours
  const float* p = mosaic.plane(0);
  // Detect on the unmodified image, then replace: the result does not depend on the order.
  std::vector<std::vector<std::pair<std::size_t, float>>> found{std::size_t(h)};
  parallelFor(0, std::size_t(h), 32, [&](std::size_t begin, std::size_t end) {
    std::array<float, 8> around;
    std::vector<int> candidates;
    for (int y = int(begin); y < int(end); ++y) {
      // Inside the image, a branch-free screen (above all 8 neighbours by the threshold) that the
      // compiler vectorises; the rare candidates and the border pixels take the general path.
      candidates.clear();
      const bool innerRow = y >= step && y < h - step;
      if (innerRow && w > 2 * step) {
        const float* above = p + std::size_t(y - step) * w;
        const float* row = p + std::size_t(y) * w;
        const float* below = p + std::size_t(y + step) * w;
        for (int x = 0; x < step; ++x) candidates.push_back(x);
        for (int x = step; x < w - step; ++x) {
          const float highest =
              std::max(std::max(std::max(above[x - step], above[x]), std::max(above[x + step], row[x - step])),
                       std::max(std::max(row[x + step], below[x - step]), std::max(below[x], below[x + step])));
          if (row[x] > highest + threshold) candidates.push_back(x);
        }
        for (int x = w - step; x < w; ++x) candidates.push_back(x);
      } else {
        for (int x = 0; x < w; ++x) candidates.push_back(x);
      }
      for (const int x : candidates) {
        const float value = p[std::size_t(y) * w + x];
        int n = 0;
        float highest = -1e30f;
        for (int dy = -step; dy <= step; dy += step)
          for (int dx = -step; dx <= step; dx += step) {
            if (dx == 0 && dy == 0) continue;
            const int xx = x + dx, yy = y + dy;
            if (xx < 0 || yy < 0 || xx >= w || yy >= h) continue;
            around[n++] = p[std::size_t(yy) * w + xx];
            highest = std::max(highest, around[n - 1]);
          }
        if (n < 3 || value <= highest + threshold) continue;
        std::nth_element(around.begin(), around.begin() + n / 2, around.begin() + n);
        found[std::size_t(y)].push_back({std::size_t(y) * w + x, around[n / 2]});
      }
    }
  });
  int repaired = 0;
  float* q = mosaic.plane(0);
  for (const auto& row : found)
    for (const auto& [index, value] : row) q[index] = value, ++repaired;
  return repaired;
}

}  // namespace lfcam
