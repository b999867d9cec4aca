// Where one view is sampled for one output pixel of a shift-and-add (refocus.hpp): the bilinear
// taps and their weights, shared by the per-pixel kernels (the float64 oracles and the tilted
// focus of tilted_focus.hpp). Internal to the library.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "lfcam/core/light_field.hpp"

namespace lfcam {

// A shift split into whole pixels and a fraction: the bilinear taps of output index x are
// x + whole and x + whole + 1 with weights 1 - fraction and fraction.
struct AxisShift {
  int whole = 0;        // floor(shift)
  double fraction = 0;  // shift - floor(shift), in [0, 1)
};

inline AxisShift shiftOf(double shift, int size) {
  // Beyond size + 1 pixels no tap lands in the view; clamping keeps floor() inside int range.
  const double limit = size + 2.0;
  shift = std::clamp(shift, -limit, limit);
  const double whole = std::floor(shift);
  return {int(whole), shift - whole};
}

// Where view (u, v) is sampled for output pixel (x, y): at column x + shiftX and row y + shiftY
// of the view, in pixel indices (the +0.5 of pixel centres cancels on both sides), with
// shift = -(view position from the centre) * slope (Equation 6: s' - u' d).
inline AxisShift axisShift(double fromCentre, double slope, int size) { return shiftOf(-fromCentre * slope, size); }

inline bool inside(int index, int size) { return index >= 0 && index < size; }

// Calls tap(row, column, weight) for each of the four bilinear taps of view (u, v) around
// (x + shiftX, y + shiftY) that lies inside the view: weight is the bilinear coefficient times the
// light field's weight (refocus.hpp).
template <typename Tap>
void forEachBilinearTap(const LightField& lightField, int u, int v, int x, int y, AxisShift shiftX, AxisShift shiftY,
                        Tap&& tap) {
  const int ns = lightField.ns(), nt = lightField.nt();
  for (int j = 0; j < 2; ++j) {
    const int row = y + shiftY.whole + j;
    if (!inside(row, nt)) continue;
    const double wy = j ? shiftY.fraction : 1 - shiftY.fraction;
    for (int i = 0; i < 2; ++i) {
      const int column = x + shiftX.whole + i;
      if (!inside(column, ns)) continue;
      double w = wy * (i ? shiftX.fraction : 1 - shiftX.fraction);
      if (lightField.hasWeight()) w *= lightField.weightPlane(u, v)[std::size_t(row) * ns + column];
      tap(row, column, w);
    }
  }
}

}  // namespace lfcam
