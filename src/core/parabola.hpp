// The minimum of a cost sampled on an even grid, between samples: the vertex of the parabola
// through the lowest sample and its two neighbours (depth's labels and fine search, the focus
// search of a focal stack). One implementation for every module.
#pragma once

#include <algorithm>

namespace lfcam {

// Offset of the vertex from the centre sample, in samples, within [-0.5, 0.5]; 0 where the three
// samples do not curve upwards (no minimum between them).
inline double parabolaVertex(double left, double centre, double right) {
  const double curvature = left - 2 * centre + right;
  return curvature > 0 ? std::clamp(0.5 * (left - right) / curvature, -0.5, 0.5) : 0.0;
}

}  // namespace lfcam
