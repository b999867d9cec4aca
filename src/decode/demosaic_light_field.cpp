// Light-field-aware demosaicing (DemosaicMethod::LightFieldAware).
//
// Why: under a defocused object, neighbouring pixels of one microlens image are neighbouring
// views, which see scene points several microlenses apart (6.7 for the test scene's far card):
// there a 2D demosaic interpolates a missing colour from unrelated content. The same view of the
// neighbouring microlenses (the same offset from their centres, one lattice vector away) sees
// nearby scene points instead, and the non-integral pitch puts it on other Bayer phases. In focus
// it is the other way round (a microlens image is flat). So each missing value is a blend of the
// two estimates, weighted by how well each domain predicts the colour that IS measured at and
// around the pixel (as Hamilton-Adams picks between horizontal and vertical):
//   1. green at red and blue photosites: Malvar-He-Cutler (2D) and the lattice neighbours' green
//      (4D: bilinear weights of the green photosites around each translated point);
//   2. red and blue from colour differences (R - G, B - G at their own photosites, smoother than
//      the colours), mean of the nearest ones (2D) or the lattice neighbours' (4D), same blend.
// Rows in parallel; `reference` takes the plain bounds-checked taps everywhere (what the fast
// precomputed taps are tested against).
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "decode/decode_internal.hpp"
#include "lfcam/parallel.hpp"

namespace lfcam::decode_detail {

namespace {

// A lattice vector's translation: integer part and the bilinear weights of the 2x2 photosites
// around the translated point (the same for every pixel).
struct Shift {
  int dx = 0, dy = 0;
  std::array<float, 4> weight{};  // (0,0), (1,0), (0,1), (1,1)
};

std::vector<Shift> latticeShifts(const LensletGrid& grid) {
  const double cs = std::cos(grid.rotationRad), sn = std::sin(grid.rotationRad);
  std::vector<std::array<double, 2>> vectors{{grid.pitchX, 0}};
  if (grid.packing == Packing::Hexagonal) {
    vectors.push_back({0.5 * grid.pitchX, grid.pitchY});
    vectors.push_back({-0.5 * grid.pitchX, grid.pitchY});
  } else {
    vectors.push_back({0, grid.pitchY});
  }
  std::vector<Shift> shifts;
  for (const auto& [a, b] : vectors)
    for (const double sign : {1.0, -1.0}) {
      const double x = sign * (cs * a - sn * b), y = sign * (sn * a + cs * b);
      Shift s;
      s.dx = int(std::floor(x)), s.dy = int(std::floor(y));
      const float fx = float(x - s.dx), fy = float(y - s.dy);
      s.weight = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
      shifts.push_back(s);
    }
  return shifts;
}

// Mean of the 4 photosites 2 pixels away (the same colour): the 2D prediction of the measured one.
template <class M>
inline float sameColourAround(const M& m, int x, int y) {
  return 0.25f * (m(x - 2, y) + m(x + 2, y) + m(x, y - 2) + m(x, y + 2));
}

}  // namespace

Image demosaicLightField(const Image& mosaic, ColorFilter filter, const LensletGrid& grid, const Image& weight,
                         bool reference) {
  const CfaTable cfa(filter);
  const int w = mosaic.width(), h = mosaic.height();
  const std::vector<Shift> shifts = latticeShifts(grid);
  const float* m = mosaic.plane(0);
  const float* lit = weight.empty() ? nullptr : weight.plane(0);
  auto index = [w](int x, int y) { return std::size_t(y) * w + x; };

  // 4D estimate of colour c at (x, y) from `src` at the photosites of colour c around the
  // translated points (weighted by their bilinear weight and how lit they are); false if none.
  // The plain version checks every tap (the reference, and the border); inside the image the taps
  // of each Bayer phase and colour are precomputed as (index offset, weight) lists.
  auto estimatePlain = [&](const float* src, int c, int x, int y, float& out) {
    float num = 0, den = 0;
    for (const Shift& s : shifts)
      for (int k = 0; k < 4; ++k) {
        const int xx = x + s.dx + (k & 1), yy = y + s.dy + (k >> 1);
        if (xx < 0 || yy < 0 || xx >= w || yy >= h || cfa(xx, yy) != c) continue;
        const float b = s.weight[std::size_t(k)] * (lit ? lit[index(xx, yy)] : 1.0f);
        num += b * src[index(xx, yy)], den += b;
      }
    if (den <= 0) return false;
    out = num / den;
    return true;
  };
  struct Taps {
    std::vector<std::ptrdiff_t> offset;
    std::vector<float> weight;
  };
  std::array<std::array<Taps, 3>, 4> taps;  // [Bayer phase (y & 1) * 2 + (x & 1)][colour]
  int margin = 2;
  for (const Shift& s : shifts) margin = std::max({margin, std::abs(s.dx) + 2, std::abs(s.dy) + 2});
  for (int phase = 0; phase < 4; ++phase)
    for (const Shift& s : shifts)
      for (int k = 0; k < 4; ++k) {
        const int ox = s.dx + (k & 1), oy = s.dy + (k >> 1);
        Taps& t = taps[std::size_t(phase)][std::size_t(cfa((phase & 1) + ox, (phase >> 1) + oy))];
        t.offset.push_back(std::ptrdiff_t(oy) * w + ox);
        t.weight.push_back(s.weight[std::size_t(k)]);
      }
  auto estimate4d = [&](const float* src, int c, int x, int y, float& out) {
    if (reference || x < margin || y < margin || x >= w - margin || y >= h - margin) return estimatePlain(src, c, x, y, out);
    const Taps& t = taps[std::size_t((y & 1) * 2 + (x & 1))][std::size_t(c)];
    const std::size_t k = index(x, y);
    const float* at = src + k;
    float num = 0, den = 0;
    if (lit) {
      const float* l = lit + k;
      for (std::size_t i = 0; i < t.offset.size(); ++i) {
        const float b = t.weight[i] * l[t.offset[i]];
        num += b * at[t.offset[i]], den += b;
      }
    } else {
      for (std::size_t i = 0; i < t.offset.size(); ++i) num += t.weight[i] * at[t.offset[i]], den += t.weight[i];
    }
    if (den <= 0) return false;
    out = num / den;
    return true;
  };
  const Mosaic reflected{m, w, h};
  const Direct direct{m, w};

  // 1. Per pixel: how well each domain predicts the measured colour (squared errors), and the two
  //    green estimates.
  std::vector<float> error2(std::size_t(w) * h), error4(std::size_t(w) * h);
  Image green(w, h, 1), green4(w, h, 1);
  parallelFor(0, std::size_t(h), 16, [&](std::size_t begin, std::size_t end) {
    for (int y = int(begin); y < int(end); ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t k = index(x, y);
        const int c = cfa(x, y);
        const bool inner = x >= 2 && y >= 2 && x < w - 2 && y < h - 2;
        const float around = inner ? sameColourAround(direct, x, y) : sameColourAround(reflected, x, y);
        float predicted = around;
        const bool has4d = estimate4d(m, c, x, y, predicted);
        // A pixel without 4D neighbours (unlit around, or at the border) does not vote.
        error2[k] = has4d ? (m[k] - around) * (m[k] - around) : 0.0f;
        error4[k] = has4d ? (m[k] - predicted) * (m[k] - predicted) : 0.0f;
        if (c == 1) {
          green.at(x, y, 0) = green4.at(x, y, 0) = m[k];
        } else {
          green.at(x, y, 0) = inner ? mhcGreenAtRB(direct, x, y) : mhcGreenAtRB(reflected, x, y);
          float g4 = green.at(x, y, 0);
          estimate4d(m, 1, x, y, g4);
          green4.at(x, y, 0) = g4;
        }
      }
  });

  // 2. Blend weight of the 4D estimate: errors summed over the 3x3 pixels around; green blended.
  std::vector<float> share4(std::size_t(w) * h);
  parallelFor(0, std::size_t(h), 16, [&](std::size_t begin, std::size_t end) {
    for (int y = int(begin); y < int(end); ++y)
      for (int x = 0; x < w; ++x) {
        double e2 = 0, e4 = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const std::size_t k = index(std::clamp(x + dx, 0, w - 1), std::clamp(y + dy, 0, h - 1));
            e2 += error2[k], e4 += error4[k];
          }
        const std::size_t k = index(x, y);
        share4[k] = float(e2 / (e2 + e4 + 1e-12));
        if (cfa(x, y) != 1) green.at(x, y, 0) = share4[k] * green4.at(x, y, 0) + (1 - share4[k]) * green.at(x, y, 0);
      }
  });
  green4 = Image();
  std::vector<float>().swap(error2);
  std::vector<float>().swap(error4);

  // 3. Colour differences at the red and blue photosites, then red and blue everywhere.
  Image difference(w, h, 1);
  const float* g = green.plane(0);
  for (std::size_t k = 0; k < std::size_t(w) * h; ++k) difference.plane(0)[k] = m[k] - g[k];
  const float* d = difference.plane(0);
  Image out(w, h, 3);
  std::copy(g, g + std::size_t(w) * h, out.plane(1));
  parallelFor(0, std::size_t(h), 16, [&](std::size_t begin, std::size_t end) {
    for (int y = int(begin); y < int(end); ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t k = index(x, y);
        const int own = cfa(x, y);
        for (const int c : {0, 2}) {
          if (c == own) {
            out.plane(c)[k] = m[k];
            continue;
          }
          // 2D: the nearest photosites of colour c (1 pixel away: 2 or 4 of them).
          float d2 = 0;
          if (x >= 1 && y >= 1 && x < w - 1 && y < h - 1) {
            const float* r = d + k;
            if (own != 1) d2 = 0.25f * (r[-w - 1] + r[-w + 1] + r[w - 1] + r[w + 1]);
            else if (cfa(x + 1, y) == c) d2 = 0.5f * (r[-1] + r[1]);
            else d2 = 0.5f * (r[-w] + r[w]);
          } else {
            float sum = 0;
            int count = 0;
            for (int dy = -1; dy <= 1; ++dy)
              for (int dx = -1; dx <= 1; ++dx) {
                const int xx = x + dx, yy = y + dy;
                if (xx < 0 || yy < 0 || xx >= w || yy >= h || cfa(xx, yy) != c) continue;
                sum += d[index(xx, yy)], ++count;
              }
            d2 = count ? sum / float(count) : 0.0f;
          }
          float d4 = d2;
          estimate4d(d, c, x, y, d4);
          out.plane(c)[k] = g[k] + share4[k] * d4 + (1 - share4[k]) * d2;
        }
      }
  });
  return out;
}

}  // namespace lfcam::decode_detail
