// Random light fields for testing fast kernels against their references.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"

namespace lfcam::test {

inline LightField randomLightField(const LightFieldShape& shape, std::mt19937& random, bool weighted) {
  LightField lightField(shape);
  std::uniform_real_distribution<float> value(0.05f, 1.0f);
  for (float& sample : lightField.samples()) sample = value(random);
  if (weighted) {
    lightField.enableWeight();
    std::uniform_real_distribution<float> weight(0.0f, 1.0f);
    // About a fifth of the samples carry no light at all, as between microlenses.
    for (float& w : lightField.weights()) w = weight(random) < 0.2f ? 0.0f : weight(random);
  }
  return lightField;
}

// Trial `trial` of a randomised comparison: up to maxViews x maxViews views of up to maxPixels x
// maxPixels pixels; odd trials in colour, every other pair of trials weighted.
inline LightField randomTrialLightField(std::mt19937& random, int trial, int maxViews, int maxPixels) {
  std::uniform_int_distribution<int> views(1, maxViews), pixels(1, maxPixels);
  const LightFieldShape shape{.nu = views(random),
                              .nv = views(random),
                              .ns = pixels(random),
                              .nt = pixels(random),
                              .channels = trial % 2 ? 3 : 1};
  return randomLightField(shape, random, trial % 4 >= 2);
}

// Largest |fast - reference| relative to max(|reference|, 1e-3); and the pixels where exactly
// one of the two is zero (no ray in one, some ray in the other) count as a failure.
inline double worstRelativeError(const Image& fast, const Image& reference) {
  double worst = 0;
  for (std::size_t i = 0; i < fast.pixels().size(); ++i) {
    const double f = fast.pixels()[i], r = reference.pixels()[i];
    if ((f == 0) != (r == 0)) return INFINITY;
    worst = std::max(worst, std::abs(f - r) / std::max(std::abs(r), 1e-3));
  }
  return worst;
}

}  // namespace lfcam::test
