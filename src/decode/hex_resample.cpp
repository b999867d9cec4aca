// Hexagonal to rectangular: the shifted rows of microlenses lie half a pitch off the others; a
// cubic at the half-way point, (-1, 9, 9, -1) / 16 along s, puts them on the common s positions.
#include <algorithm>
#include <vector>

#include "core/parallel.hpp"
#include "lfcam/decode/decode.hpp"

namespace lfcam {

namespace {

// Row `row` of n samples, whose sample s lies at s + 1/2: values at the whole positions s.
void halfShiftRow(float* row, int n, std::vector<float>& scratch, bool clampToUnit) {
  scratch.assign(row, row + n);
  auto at = [&](int s) { return scratch[std::size_t(std::clamp(s, 0, n - 1))]; };
  for (int s = 0; s < n; ++s) {
    float value = (-at(s - 2) + 9 * at(s - 1) + 9 * at(s) - at(s + 1)) * (1.0f / 16);
    if (clampToUnit) value = std::clamp(value, 0.0f, 1.0f);
    row[s] = value;
  }
}

}  // namespace

void hexRowsToRectangular(LightField& lightField, int shiftedT) {
  const int ns = lightField.ns(), nt = lightField.nt();
  const std::size_t planes = lightField.shape().views() * lightField.channels();
  const std::size_t views = lightField.shape().views();
  const std::size_t pixels = lightField.shape().viewPixels();
  float* samples = lightField.samples().data();
  float* weights = lightField.hasWeight() ? lightField.weights().data() : nullptr;
  parallelFor(0, planes + (weights ? views : 0), 4, [&](std::size_t begin, std::size_t end) {
    std::vector<float> scratch;
    for (std::size_t p = begin; p < end; ++p) {
      const bool isWeight = p >= planes;
      float* plane = isWeight ? weights + (p - planes) * pixels : samples + p * pixels;
      for (int t = (shiftedT & 1); t < nt; t += 2) halfShiftRow(plane + std::size_t(t) * ns, ns, scratch, isWeight);
    }
  });
}

}  // namespace lfcam
