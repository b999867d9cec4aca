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
//   1. green at red and blue photosites: Hamilton-Adams's (2D; 0.13 dB better here than
//      Malvar-He-Cutler's) and the lattice neighbours' green (4D: bilinear weights of the green
//      photosites around each translated point);
//   2. red and blue from colour differences (R - G, B - G at their own photosites, smoother than
//      the colours), mean of the nearest ones (2D) or the lattice neighbours' (4D), same blend.
// Two implementations: the reference, one plain pass per step over whole planes with
// bounds-checked taps, and the fast one, which fuses the steps into two row-parallel passes
// writing only the output (its intermediate planes, freshly faulted in, were a visible share of
// the time), with the taps precomputed per Bayer phase inside the image.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/parallel.hpp"
#include "decode/decode_internal.hpp"

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
inline float sameColorAround(const M& m, int x, int y) {
  return 0.25f * (m(x - 2, y) + m(x + 2, y) + m(x, y - 2) + m(x, y + 2));
}

// The 4D estimate of colour c at (x, y): the values (`value(k)`, k a photosite's index) of the
// photosites of colour c around the translated points, weighted by their bilinear weight and how
// lit they are; false if none. `plain` checks every tap (the reference, and the border);
// `insideFixed` (at least `margin` from every border) reads precomputed (index offset, weight) lists.
class LatticeTaps {
 public:
  LatticeTaps(const LensletGrid& grid, const CfaTable& cfa, int width, int height, const float* lit)
      : shifts_(latticeShifts(grid)), cfa_(cfa), w_(width), h_(height), lit_(lit) {
    for (const Shift& s : shifts_) margin = std::max({margin, std::abs(s.dx) + 2, std::abs(s.dy) + 2});
    for (int phase = 0; phase < 4; ++phase)
      for (const Shift& s : shifts_)
        for (int k = 0; k < 4; ++k) {
          const int ox = s.dx + (k & 1), oy = s.dy + (k >> 1);
          List& t = lists_[std::size_t(phase)][std::size_t(cfa((phase & 1) + ox, (phase >> 1) + oy))];
          t.offset[std::size_t(t.count)] = std::ptrdiff_t(oy) * w_ + ox;
          t.weight[std::size_t(t.count)] = s.weight[std::size_t(k)];
          ++t.count;
        }
  }

  template <class V>
  bool plain(const V& value, int c, int x, int y, float& out) const {
    float num = 0, den = 0;
    for (const Shift& s : shifts_)
      for (int k = 0; k < 4; ++k) {
        const int xx = x + s.dx + (k & 1), yy = y + s.dy + (k >> 1);
        if (xx < 0 || yy < 0 || xx >= w_ || yy >= h_ || cfa_(xx, yy) != c) continue;
        const std::size_t i = std::size_t(yy) * w_ + xx;
        const float b = s.weight[std::size_t(k)] * (lit_ ? lit_[i] : 1.0f);
        num += b * value(i), den += b;
      }
    if (den <= 0) return false;
    out = num / den;
    return true;
  }

  // Inside the image, with the tap count known when compiling: each lattice vector's 2x2 photosites hold
  // one red, one blue and two greens, so N is the number of lattice vectors for red and blue, and
  // twice that for green. k: the pixel's index; phase: (y & 1) * 2 + (x & 1).
  template <int N, bool HasLit, class V>
  bool insideFixed(const V& value, int c, int phase, std::size_t k, float& out) const {
    const List& t = lists_[std::size_t(phase)][std::size_t(c)];
    float num = 0, den = 0;
    for (int i = 0; i < N; ++i) {
      const std::size_t at = std::size_t(std::ptrdiff_t(k) + t.offset[std::size_t(i)]);
      const float b = HasLit ? t.weight[std::size_t(i)] * lit_[at] : t.weight[std::size_t(i)];
      num += b * value(at), den += b;
    }
    if (den <= 0) return false;
    out = num / den;
    return true;
  }
  int shifts() const { return int(shifts_.size()); }

  // Near the borders (the fast path's only use of it): every tap checked.
  template <class V>
  bool operator()(const V& value, int c, int x, int y, float& out) const {
    return plain(value, c, x, y, out);
  }

  int margin = 2;

 private:
  struct List {
    int count = 0;
    std::array<std::ptrdiff_t, 24> offset{};  // up to 6 lattice vectors x 4 corners
    std::array<float, 24> weight{};
  };
  std::vector<Shift> shifts_;
  CfaTable cfa_;
  int w_, h_;
  const float* lit_;
  std::array<std::array<List, 3>, 4> lists_{};  // [Bayer phase (y & 1) * 2 + (x & 1)][colour]
};

// 2D estimate of the colour difference `d` (R - G or B - G) of colour c at (x, y): the mean of the
// nearest photosites of colour c (1 pixel away: 2 or 4 of them).
template <class D>
inline float nearestDifference(const D& d, const CfaTable& cfa, int own, int c, int x, int y, int w, int h) {
  const std::size_t k = std::size_t(y) * w + x;
  if (x >= 1 && y >= 1 && x < w - 1 && y < h - 1) {
    if (own != 1) return 0.25f * (d(k - w - 1) + d(k - w + 1) + d(k + w - 1) + d(k + w + 1));
    if (cfa(x + 1, y) == c) return 0.5f * (d(k - 1) + d(k + 1));
    return 0.5f * (d(k - w) + d(k + w));
  }
  float sum = 0;
  int count = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int xx = x + dx, yy = y + dy;
      if (xx < 0 || yy < 0 || xx >= w || yy >= h || cfa(xx, yy) != c) continue;
      sum += d(std::size_t(yy) * w + xx), ++count;
    }
  return count ? sum / float(count) : 0.0f;
}

// The squared errors of the 2D and 4D predictions of the colour measured at (x, y). A pixel without
// 4D neighbours (unlit around, or at the border) does not vote.
template <class Estimate>
inline void predictionErrors(const float* m, const CfaTable& cfa, const Estimate& estimate, int x, int y, int w, int h,
                             float& e2, float& e4) {
  const std::size_t k = std::size_t(y) * w + x;
  const bool inner = x >= 2 && y >= 2 && x < w - 2 && y < h - 2;
  const float around = inner ? sameColorAround(Direct{m, w}, x, y) : sameColorAround(Mosaic{m, w, h}, x, y);
  float predicted = around;
  const bool has4d = estimate([m](std::size_t i) { return m[i]; }, cfa(x, y), x, y, predicted);
  e2 = has4d ? (m[k] - around) * (m[k] - around) : 0.0f;
  e4 = has4d ? (m[k] - predicted) * (m[k] - predicted) : 0.0f;
}

// The 2D green at a red or blue photosite.
inline float green2d(const float* m, int x, int y, int w, int h) {
  return x >= 2 && y >= 2 && x < w - 2 && y < h - 2 ? haGreen(Direct{m, w}, x, y) : haGreen(Mosaic{m, w, h}, x, y);
}

// The reference: each step a pass over whole planes, every tap bounds-checked.
Image demosaicReferencePasses(const Image& mosaic, const CfaTable& cfa, const LatticeTaps& taps) {
  const int w = mosaic.width(), h = mosaic.height();
  const float* m = mosaic.plane(0);
  auto index = [w](int x, int y) { return std::size_t(y) * w + x; };
  auto plain = [&](const auto& value, int c, int x, int y, float& out) { return taps.plain(value, c, x, y, out); };

  // 1. Per pixel: how well each domain predicts the measured colour, and the two green estimates.
  std::vector<float> error2(std::size_t(w) * h), error4(std::size_t(w) * h);
  Image green(w, h, 1), green4(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t k = index(x, y);
      predictionErrors(m, cfa, plain, x, y, w, h, error2[k], error4[k]);
      if (cfa(x, y) == 1) {
        green.at(x, y, 0) = green4.at(x, y, 0) = m[k];
      } else {
        green.at(x, y, 0) = green4.at(x, y, 0) = green2d(m, x, y, w, h);
        taps.plain([m](std::size_t i) { return m[i]; }, 1, x, y, green4.at(x, y, 0));
      }
    }

  // 2. Blend weight of the 4D estimate: errors summed over the 3x3 pixels around; green blended.
  std::vector<float> share4(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
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

  // 3. Colour differences at the red and blue photosites, then red and blue everywhere.
  std::vector<float> difference(std::size_t(w) * h);
  const float* g = green.plane(0);
  for (std::size_t k = 0; k < difference.size(); ++k) difference[k] = m[k] - g[k];
  auto d = [&difference](std::size_t i) { return difference[i]; };
  Image out(w, h, 3);
  std::copy(g, g + std::size_t(w) * h, out.plane(1));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t k = index(x, y);
      const int own = cfa(x, y);
      for (const int c : {0, 2}) {
        if (c == own) {
          out.plane(c)[k] = m[k];
          continue;
        }
        const float d2 = nearestDifference(d, cfa, own, c, x, y, w, h);
        float d4 = d2;
        taps.plain(d, c, x, y, d4);
        out.plane(c)[k] = g[k] + share4[k] * d4 + (1 - share4[k]) * d2;
      }
    }
  return out;
}

// The fast one: pass A computes the prediction errors a few rows at a time (a ring of 3 rows per
// band of rows), the share of the 4D estimate (parked in the red plane) and the blended green;
// pass B reads the colour differences as mosaic - green on the fly and writes red and blue.
// Inside the margin the taps are fixed lists (Shifts lattice vectors; HasLit: a weight is given).
template <int Shifts, bool HasLit>
Image demosaicFused(const Image& mosaic, const CfaTable& cfa, const LatticeTaps& taps) {
  const int w = mosaic.width(), h = mosaic.height(), margin = taps.margin;
  const float* m = mosaic.plane(0);
  Image out(w, h, 3);
  float* red = out.plane(0);
  float* green = out.plane(1);
  float* blue = out.plane(2);
  auto mosaicValue = [m](std::size_t i) { return m[i]; };
  auto difference = [m, green](std::size_t i) { return m[i] - green[i]; };
  // `general(x)` near the borders, `inner(x, k, phase)` at least `margin` from every border.
  auto forRow = [&](int y, auto&& general, auto&& inner) {
    const bool innerRow = y >= margin && y < h - margin;
    const int x0 = innerRow ? margin : w, x1 = innerRow ? w - margin : w;
    for (int x = 0; x < std::min(x0, w); ++x) general(x);
    const std::size_t row = std::size_t(y) * w;
    const int rowPhase = (y & 1) * 2;
    for (int x = x0; x < x1; ++x) inner(x, row + x, rowPhase + (x & 1));
    for (int x = std::max(x1, x0); x < w; ++x) general(x);
  };
  auto estimate = [&](const auto& value, int c, int phase, std::size_t k, float& v) {
    return c == 1 ? taps.template insideFixed<2 * Shifts, HasLit>(value, 1, phase, k, v)
                  : taps.template insideFixed<Shifts, HasLit>(value, c, phase, k, v);
  };

  parallelFor(0, std::size_t(h), 32, [&](std::size_t begin, std::size_t end) {
    // Ring of error rows: slot y % 3 holds row `rowOf[slot]`.
    std::vector<float> e2(3 * std::size_t(w)), e4(3 * std::size_t(w)), sum2(std::size_t(w) + 2),
        sum4(std::size_t(w) + 2);
    std::array<int, 3> rowOf{-1, -1, -1};
    auto errorRow = [&](int y) {
      const std::size_t slot = std::size_t(y % 3), at = slot * std::size_t(w);
      if (rowOf[slot] != y) {
        forRow(
            y, [&](int x) { predictionErrors(m, cfa, taps, x, y, w, h, e2[at + x], e4[at + x]); },
            [&](int x, std::size_t k, int phase) {
              const float around =
                  0.25f * (m[k - 2] + m[k + 2] + m[k - 2 * std::size_t(w)] + m[k + 2 * std::size_t(w)]);
              float predicted = around;
              const bool has4d = estimate(mosaicValue, cfa.phase[std::size_t(phase)], phase, k, predicted);
              e2[at + x] = has4d ? (m[k] - around) * (m[k] - around) : 0.0f;
              e4[at + x] = has4d ? (m[k] - predicted) * (m[k] - predicted) : 0.0f;
            });
        rowOf[slot] = y;
      }
      return at;
    };
    for (int y = int(begin); y < int(end); ++y) {
      const std::size_t up = errorRow(std::max(y - 1, 0)), mid = errorRow(y), down = errorRow(std::min(y + 1, h - 1));
      // Column sums, the border column repeated (the reference clamps).
      for (int x = 0; x < w; ++x) {
        sum2[std::size_t(x) + 1] = e2[up + x] + e2[mid + x] + e2[down + x];
        sum4[std::size_t(x) + 1] = e4[up + x] + e4[mid + x] + e4[down + x];
      }
      sum2[0] = sum2[1], sum4[0] = sum4[1], sum2[std::size_t(w) + 1] = sum2[std::size_t(w)],
      sum4[std::size_t(w) + 1] = sum4[std::size_t(w)];
      const std::size_t row = std::size_t(y) * w;
      for (int x = 0; x < w; ++x) {
        const float s2 = sum2[std::size_t(x)] + sum2[std::size_t(x) + 1] + sum2[std::size_t(x) + 2];
        const float s4 = sum4[std::size_t(x)] + sum4[std::size_t(x) + 1] + sum4[std::size_t(x) + 2];
        red[row + x] = s2 / (s2 + s4 + 1e-12f);
      }
      forRow(
          y,
          [&](int x) {
            const std::size_t k = row + x;
            if (cfa(x, y) == 1) {
              green[k] = m[k];
              return;
            }
            const float g2 = green2d(m, x, y, w, h);
            float g4 = g2;
            taps(mosaicValue, 1, x, y, g4);
            green[k] = red[k] * g4 + (1 - red[k]) * g2;
          },
          [&](int x, std::size_t k, int phase) {
            if (cfa.phase[std::size_t(phase)] == 1) {
              green[k] = m[k];
              return;
            }
            const float g2 = haGreen(Direct{m, w}, x, y);
            float g4 = g2;
            estimate(mosaicValue, 1, phase, k, g4);
            green[k] = red[k] * g4 + (1 - red[k]) * g2;
          });
    }
  });

  parallelFor(0, std::size_t(h), 16, [&](std::size_t begin, std::size_t end) {
    for (int y = int(begin); y < int(end); ++y)
      forRow(
          y,
          [&](int x) {
            const std::size_t k = std::size_t(y) * w + x;
            const int own = cfa(x, y);
            const float share = red[k], g = green[k];
            float rb[2];
            for (const int c : {0, 2}) {
              float& v = rb[c / 2];
              if (c == own) {
                v = m[k];
                continue;
              }
              const float d2 = nearestDifference(difference, cfa, own, c, x, y, w, h);
              float d4 = d2;
              taps(difference, c, x, y, d4);
              v = g + share * d4 + (1 - share) * d2;
            }
            red[k] = rb[0], blue[k] = rb[1];
          },
          [&](int x, std::size_t k, int phase) {
            const int own = cfa.phase[std::size_t(phase)];
            const float share = red[k], g = green[k];
            if (own == 1) {
              // Red and blue: the nearest two across or down, as the row's colours fall.
              const bool redAcross = cfa(x + 1, y) == 0;
              const float across = 0.5f * (difference(k - 1) + difference(k + 1)),
                          down = 0.5f * (difference(k - std::size_t(w)) + difference(k + std::size_t(w)));
              const float r2 = redAcross ? across : down, b2 = redAcross ? down : across;
              float r4 = r2, b4 = b2;
              estimate(difference, 0, phase, k, r4);
              estimate(difference, 2, phase, k, b4);
              red[k] = g + share * r4 + (1 - share) * r2;
              blue[k] = g + share * b4 + (1 - share) * b2;
              return;
            }
            // At red, blue from the four diagonal neighbours (and the other way round).
            const std::size_t wu = std::size_t(w);
            const float d2 = 0.25f * (difference(k - wu - 1) + difference(k - wu + 1) + difference(k + wu - 1) +
                                      difference(k + wu + 1));
            float d4 = d2;
            estimate(difference, 2 - own, phase, k, d4);
            const float other = g + share * d4 + (1 - share) * d2;
            red[k] = own == 0 ? m[k] : other;
            blue[k] = own == 0 ? other : m[k];
          });
  });
  return out;
}

}  // namespace

Image demosaicLightField(const Image& mosaic, ColorFilter filter, const LensletGrid& grid, const Image& weight,
                         bool reference) {
  const CfaTable cfa(filter);
  const LatticeTaps taps(grid, cfa, mosaic.width(), mosaic.height(), weight.empty() ? nullptr : weight.plane(0));
  if (reference) return demosaicReferencePasses(mosaic, cfa, taps);
  const bool lit = !weight.empty();
  if (taps.shifts() == 6)
    return lit ? demosaicFused<6, true>(mosaic, cfa, taps) : demosaicFused<6, false>(mosaic, cfa, taps);
  return lit ? demosaicFused<4, true>(mosaic, cfa, taps) : demosaicFused<4, false>(mosaic, cfa, taps);
}

}  // namespace lfcam::decode_detail
