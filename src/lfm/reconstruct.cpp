#include "lfcam/lfm/reconstruct.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "core/parallel.hpp"

namespace lfcam {

namespace {

double norm(std::span<const float> values) {
  double sum = 0;
  for (float v : values) sum += double(v) * v;
  return std::sqrt(sum);
}

// The divergence of grad x / |grad x| (forward differences, backward for the divergence), voxel
// units in all three directions: the total-variation term of Dey et al.'s RL-TV.
std::vector<float> tvDivergence(const Volume& x) {
  const int w = x.width(), h = x.height(), d = x.depth();
  const std::size_t size = x.voxels().size();
  std::vector<float> gx(size), gy(size), gz(size);
  auto at = [&](int i, int j, int k) {
    return x.at(std::clamp(i, 0, w - 1), std::clamp(j, 0, h - 1), std::clamp(k, 0, d - 1));
  };
  parallelFor(0, d, 1, [&](std::size_t begin, std::size_t end) {
    for (int k = int(begin); k < int(end); ++k)
      for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
          const float v = x.at(i, j, k);
          const float dx = at(i + 1, j, k) - v, dy = at(i, j + 1, k) - v, dz = at(i, j, k + 1) - v;
          const float length = std::sqrt(dx * dx + dy * dy + dz * dz) + 1e-12f * (std::abs(v) + 1e-12f);
          const std::size_t index = (std::size_t(k) * h + j) * w + i;
          gx[index] = dx / length, gy[index] = dy / length, gz[index] = dz / length;
        }
  });
  std::vector<float> divergence(size);
  parallelFor(0, d, 1, [&](std::size_t begin, std::size_t end) {
    for (int k = int(begin); k < int(end); ++k)
      for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
          const std::size_t index = (std::size_t(k) * h + j) * w + i;
          float sum = gx[index] + gy[index] + gz[index];
          if (i > 0) sum -= gx[index - 1];
          if (j > 0) sum -= gy[index - w];
          if (k > 0) sum -= gz[index - std::size_t(w) * h];
          divergence[index] = sum;
        }
  });
  return divergence;
}

}  // namespace

Result<LfmReconstruction> reconstructVolume(const LfmProjector& projector, const Image& frame,
                                            const LfmReconstructOptions& options, const ProgressCallback& progress,
                                            const Image* radiometry) {
  const int n = projector.psf().grid.pixelsPerLenslet;
  if (frame.channels() != 1 || frame.width() != projector.lensletsX() * n ||
      frame.height() != projector.lensletsY() * n)
    return makeError(ErrorCode::Usage, "the frame is " + std::to_string(frame.width()) + " x " +
                                           std::to_string(frame.height()) + " x " + std::to_string(frame.channels()) +
                                           ", not the projector's " + std::to_string(projector.lensletsX() * n) +
                                           " x " + std::to_string(projector.lensletsY() * n) + " x 1");
  if (radiometry &&
      (radiometry->width() != frame.width() || radiometry->height() != frame.height() || radiometry->channels() != 1))
    return makeError(ErrorCode::Usage, "the radiometry is not the frame's size");
  if (options.iterations < 1 || options.iterations > 10000)
    return makeError(ErrorCode::Usage, "iterations " + std::to_string(options.iterations) + " outside [1, 10000]");
  auto finiteAtLeastZero = [](double x) { return x >= 0 && std::isfinite(x); };
  if (!finiteAtLeastZero(options.tolerance) || !finiteAtLeastZero(options.background) ||
      !finiteAtLeastZero(options.tvWeight))
    return makeError(ErrorCode::Usage, "tolerance, background and TV weight must be finite and >= 0");
  if (options.tvWeight >= 1)
    return makeError(ErrorCode::Usage, "TV weight must be below 1: RL-TV divides by 1 - lambda div(...)");

  Image y(frame.width(), frame.height(), 1);
  for (std::size_t i = 0; i < y.pixels().size(); ++i) {
    const float v = frame.pixels()[i];
    y.pixels()[i] = std::isfinite(v) ? std::max(v, 0.0f) : 0.0f;
  }
  // H' = diag(R) H: its forward projection R (H x), its back projection H^T (R f).
  auto forward = [&](const Volume& volume) {
    Image out = projector.forward(volume);
    if (radiometry)
      for (std::size_t i = 0; i < out.pixels().size(); ++i) out.pixels()[i] *= radiometry->pixels()[i];
    return out;
  };
  auto backward = [&](Image f) {
    if (radiometry)
      for (std::size_t i = 0; i < f.pixels().size(); ++i) f.pixels()[i] *= radiometry->pixels()[i];
    return projector.backward(f);
  };
  Volume sensitivity;  // H'^T 1
  if (radiometry) {
    Image r = radiometry->copy();
    for (float& v : r.pixels()) v = std::isfinite(v) ? std::max(v, 0.0f) : 0.0f;
    sensitivity = projector.backward(r);
  } else {
    sensitivity = projector.sensitivity();
  }
  // The normalised back-projection: the solution's first estimate and the cheap alternative.
  Volume x = backward(y.copy());
  for (std::size_t i = 0; i < x.voxels().size(); ++i) {
    const float s = sensitivity.voxels()[i];
    x.voxels()[i] = s > 0 ? x.voxels()[i] / s : 0.0f;
  }
  LfmReconstruction result;
  if (options.solver == LfmSolver::BackProjection) {
    result.volume = std::move(x);
    if (progress) progress(1);
    return result;
  }
  const double yNorm = std::max(norm(y.pixels()), 1e-30);
  const float background = float(options.background);
  // |y - (H x + b)| / |y|, and y / (H x + b) into `ratio`.
  auto compare = [&](const Volume& volume, Image& ratio) {
    const Image estimate = forward(volume);
    double residual = 0;
    for (std::size_t i = 0; i < y.pixels().size(); ++i) {
      const float e = estimate.pixels()[i] + background, observed = y.pixels()[i];
      residual += double(observed - e) * (observed - e);
      ratio.pixels()[i] = e > 0 ? observed / e : 0.0f;
    }
    return std::sqrt(residual) / yNorm;
  };
  Image ratio(frame.width(), frame.height(), 1);
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    result.residuals.push_back(compare(x, ratio));
    const Volume correction = backward(ratio.copy());
    std::vector<float> divergence;
    if (options.tvWeight > 0) divergence = tvDivergence(x);
    double change = 0;
    for (std::size_t i = 0; i < x.voxels().size(); ++i) {
      const float s = sensitivity.voxels()[i];
      float denominator = s;
      if (!divergence.empty()) denominator *= std::max(1.0f - float(options.tvWeight) * divergence[i], 1e-3f);
      const float next = s > 0 ? x.voxels()[i] * correction.voxels()[i] / denominator : 0.0f;
      change += double(next - x.voxels()[i]) * (next - x.voxels()[i]);
      x.voxels()[i] = next;
    }
    result.iterations = iteration + 1;
    if (progress) progress(double(iteration + 1) / options.iterations);
    if (cancellationRequested()) break;
    if (options.tolerance > 0 && std::sqrt(change) <= options.tolerance * std::max(norm(x.voxels()), 1e-30)) break;
  }
  result.volume = std::move(x);
  return result;
}

Image simulateLfmFrame(const LfmProjector& projector, const Volume& volume, double background, double photonsPerUnit,
                       std::uint64_t seed) {
  Image frame = projector.forward(volume);
  std::mt19937_64 random(seed);
  for (float& value : frame.pixels()) {
    const double expected = std::max(0.0, double(value) + background);
    if (photonsPerUnit <= 0) {
      value = float(expected);
      continue;
    }
    std::poisson_distribution<long long> photons(expected * photonsPerUnit);
    value = float(expected > 0 ? double(photons(random)) / photonsPerUnit : 0.0);
  }
  return frame;
}

}  // namespace lfcam
