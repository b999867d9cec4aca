// The views' brightness offsets from the reference view, measured and removed (depth_stages.hpp).
#include <algorithm>
#include <cmath>
#include <utility>

#include "core/bilinear.hpp"
#include "core/parallel.hpp"
#include "edof/depth_stages.hpp"

namespace lfcam::edof {

namespace {

// The largest map error (pixels per view step) that mapError gives removeViewOffsets to take out:
// beyond it the fit meets an occlusion edge or no texture, not a small bias.
constexpr double kOffsetSlopeLimit = 0.5;

// The error of a map by which views were warped onto the reference, per pixel, as the part of
// each view's difference from the reference that the error explains: its slope g (the reference's
// gradient `dx`, `dy` along the view's baseline, times -1: an error e moves the view's samples by
// -e (u, v), so g = -(u dx + v dy) for the view steps `steps(u, v)` gives) times the error, fitted
// to all views at once by least squares over a box of `radius`, with an offset and a gain per view
// free in it (a sheen adds to the texture and scales it), so that only texture decides. Clamped to
// +-kOffsetSlopeLimit. `differences`: each view's, warped, less the reference (none for the
// reference). g being linear in the view steps, its box means (of g, g g, g r, d g) follow from
// those of the gradient and its products, made once, and of d dx and d dy: three or four box filters
// per view where six were (the same sums, rounded otherwise).
template <typename Steps, typename IsReference>
std::vector<float> mapError(const LightField& grey, const std::vector<float>& reference, int radius,
                            const std::vector<std::vector<float>>& differences, const std::vector<float>& dx,
                            const std::vector<float>& dy, const Steps& steps, const IsReference& isReference) {
  const int ns = grey.ns(), nt = grey.nt();
  const std::size_t n = grey.shape().viewPixels();
  std::vector<float> meanReference(n), meanSquare(n), square(n);
  boxFilter(reference.data(), meanReference.data(), ns, nt, radius);
  for (std::size_t i = 0; i < n; ++i) square[i] = reference[i] * reference[i];
  boxFilter(square.data(), meanSquare.data(), ns, nt, radius);
  // Box means of dx, dy, dx dx, dx dy, dy dy, dx r, dy r (a factor of none: the plane itself).
  enum { kX, kY, kXX, kXY, kYY, kXR, kYR, kGradientMeans };
  const std::vector<float>* factors[kGradientMeans][2] = {
      {&dx, nullptr}, {&dy, nullptr}, {&dx, &dx}, {&dx, &dy}, {&dy, &dy}, {&dx, &reference}, {&dy, &reference}};
  std::vector<float> gradientMean[kGradientMeans];
  parallelFor(0, kGradientMeans, 1, [&](std::size_t begin, std::size_t end) {
    std::vector<float> product(n);
    for (std::size_t k = begin; k < end; ++k) {
      const std::vector<float>& a = *factors[k][0];
      if (factors[k][1])
        for (std::size_t i = 0; i < n; ++i) product[i] = a[i] * (*factors[k][1])[i];
      gradientMean[k].resize(n);
      boxFilter(factors[k][1] ? product.data() : a.data(), gradientMean[k].data(), ns, nt, radius);
    }
  });
  // Sums over the views in an order that the threads do not change (the same map from every run):
  // views dealt by index to kSumGroups groups, each summed in order, then the groups in order.
  constexpr std::size_t kSumGroups = 8;
  std::vector<double> groupCovariance[kSumGroups], groupVariance[kSumGroups];
  const std::size_t views = grey.shape().views();
  parallelFor(0, kSumGroups, 1, [&](std::size_t begin, std::size_t end) {
    std::vector<float> product(n), mean[4];  // of d, d r, d dx, d dy
    for (auto& m : mean) m.resize(n);
    const auto boxOfProduct = [&](const std::vector<float>& a, const std::vector<float>& b, std::vector<float>& out) {
      for (std::size_t i = 0; i < n; ++i) product[i] = a[i] * b[i];
      boxFilter(product.data(), out.data(), ns, nt, radius);
    };
    for (std::size_t group = begin; group < end; ++group) {
      std::vector<double>& localCovariance = groupCovariance[group];
      std::vector<double>& localVariance = groupVariance[group];
      localCovariance.assign(n, 0.0), localVariance.assign(n, 0.0);
      for (std::size_t view = group; view < views; view += kSumGroups) {
        if (isReference(view)) continue;
        const auto [uc, vc] = steps(int(view % grey.nu()), int(view / grey.nu()));
        const std::vector<float>& difference = differences[view];
        boxFilter(difference.data(), mean[0].data(), ns, nt, radius);
        boxOfProduct(difference, reference, mean[1]);
        if (uc != 0) boxOfProduct(difference, dx, mean[2]);
        if (vc != 0) boxOfProduct(difference, dy, mean[3]);
        for (std::size_t i = 0; i < n; ++i) {
          const auto at = [&](int k) { return double(gradientMean[k][i]); };
          const double d = mean[0][i], g = -(uc * at(kX) + vc * at(kY));
          const double dgMean = -((uc != 0 ? uc * mean[2][i] : 0.0) + (vc != 0 ? vc * mean[3][i] : 0.0));
          const double ggMean = uc * uc * at(kXX) + 2 * uc * vc * at(kXY) + vc * vc * at(kYY);
          const double grMean = -(uc * at(kXR) + vc * at(kYR));
          // Covariances over the box; the reference's part (the gain) projected out where it varies.
          const double r = meanReference[i], rr = double(meanSquare[i]) - r * r;
          const double dg = dgMean - d * g, gg = ggMean - g * g;
          const double dr = double(mean[1][i]) - d * r, gr = grMean - g * r;
          const bool gain = rr > 1e-12;
          localCovariance[i] += gain ? dg - dr * gr / rr : dg;
          localVariance[i] += gain ? gg - gr * gr / rr : gg;
        }
      }
    }
  });
  std::vector<double> covariance(n, 0.0), variance(n, 0.0);
  for (std::size_t group = 0; group < kSumGroups; ++group)
    for (std::size_t i = 0; i < groupCovariance[group].size(); ++i)
      covariance[i] += groupCovariance[group][i], variance[i] += groupVariance[group][i];
  std::vector<float> error(n, 0.0f);
  for (std::size_t i = 0; i < n; ++i)
    if (variance[i] > 0)
      error[i] = float(std::clamp(covariance[i] / variance[i], -kOffsetSlopeLimit, kOffsetSlopeLimit));
  return error;
}

// Where the centre view's texture is locally a ramp (features far wider than the box, the layered
// planes of coarse texture at 256 px per view), a map error e gives each view the difference e g
// with g constant over the box: mapError, which leaves each view an offset free, cannot see it,
// and the average takes it for an offset, which then cancels the views' disagreement at the
// wrong disparity and keeps it (that scene 32.73 % with the view offsets, 5.06 % without). The
// shrink (DepthExperiment::offsetShrink, off by default) keeps an offset only where it is larger
// than a map error of kOffsetMapErrorPx would make: before offsetsKept (below), development means
// 2.200 -> 1.921 % at 128 px per view and 3.175 -> 2.002 % at 256 (the coarse texture 12.55 ->
// 3.67 and 32.73 -> 8.19 %), but a sheen on texture is taken for a map error too (the glossy
// unevenly lit slants 3.40 -> 7.42 % at 128) and the tests of the view offsets refuse it
// (design.md, "Depth"). Among 0.15, 0.2, 0.3 and 1 px, 0.3 had the best means.
constexpr double kOffsetMapErrorPx = 0.3;

}  // namespace

void removeViewOffsets(LightField& grey, const Image& disparity, int radius, double epsilon, bool slopeCorrected,
                       bool shrunk, bool fromReference, const std::vector<float>* kept) {
  const int ns = grey.ns(), nt = grey.nt();
  const std::size_t n = grey.shape().viewPixels();
  const int referenceU = (grey.nu() - 1) / 2, referenceV = (grey.nv() - 1) / 2;
  const auto warp = [&](int u, int v, float* out) {
    const float* plane = grey.plane(u, v, 0);
    const double uc = stepsU(grey, u, fromReference), vc = stepsV(grey, v, fromReference);
    for (int y = 0; y < nt; ++y)
      for (int x = 0; x < ns; ++x) {
        const double d = disparity.at(x, y, 0);
        out[std::size_t(y) * ns + x] = bilinearSample(plane, ns, nt, x - uc * d, double(y) - vc * d);
      }
  };
  const auto isReference = [&](std::size_t view) {
    return int(view % grey.nu()) == referenceU && int(view / grey.nu()) == referenceV;
  };
  const bool slopes = slopeCorrected || shrunk;
  std::vector<float> reference(n), dx(slopes ? n : 0), dy(slopes ? n : 0), error;
  warp(referenceU, referenceV, reference.data());
  const auto slope = [&](int u, int v, float* out) {
    const float uc = float(stepsU(grey, u, fromReference)), vc = float(stepsV(grey, v, fromReference));
    for (std::size_t i = 0; i < n; ++i) out[i] = -(uc * dx[i] + vc * dy[i]);
  };
  if (slopes) centralDifferences(reference.data(), ns, nt, 1.0f, dx.data(), dy.data());
  // Each view warped once, for both the map's error and the offsets (a view's worth of memory each).
  std::vector<std::vector<float>> differences(grey.shape().views());
  parallelFor(0, grey.shape().views(), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t view = begin; view < end; ++view) {
      if (isReference(view)) continue;
      std::vector<float>& difference = differences[view];
      difference.resize(n);
      warp(int(view % grey.nu()), int(view / grey.nu()), difference.data());
      for (std::size_t i = 0; i < n; ++i) difference[i] -= reference[i];
    }
  });
  const auto steps = [&](int u, int v) {
    return std::pair{stepsU(grey, u, fromReference), stepsV(grey, v, fromReference)};
  };
  if (slopeCorrected) error = mapError(grey, reference, radius, differences, dx, dy, steps, isReference);
  const edof::GuidedFilter filter(disparity.plane(0), ns, nt, radius, epsilon);
  parallelFor(0, grey.shape().views(), 1, [&](std::size_t begin, std::size_t end) {
    std::vector<float> offset(n), g(dx.size());
    edof::GuidedFilter::Scratch scratch;
    for (std::size_t view = begin; view < end; ++view) {
      if (isReference(view)) continue;
      const int u = int(view % grey.nu()), v = int(view / grey.nu());
      std::vector<float>& difference = differences[view];
      if (slopes) slope(u, v, g.data());
      if (slopeCorrected)
        for (std::size_t i = 0; i < n; ++i) difference[i] -= error[i] * g[i];
      filter.apply(difference.data(), offset.data(), scratch);
      difference = std::vector<float>();  // done with
      if (shrunk)
        for (std::size_t i = 0; i < n; ++i) {
          const double squared = double(offset[i]) * offset[i], explained = kOffsetMapErrorPx * g[i];
          if (squared > 0) offset[i] = float(offset[i] * squared / (squared + explained * explained));
        }
      float* plane = grey.plane(u, v, 0);
      for (std::size_t i = 0; i < n; ++i) plane[i] -= kept ? (*kept)[i] * offset[i] : offset[i];
    }
  });
}

namespace {

// Where the view offsets are kept: where the half resolution's match after their removal leaves the
// views disagreeing no more than its match before, give or take kOffsetCheckTolerance times the
// median of `before` (`after` <= `before` + that, per half-resolution pixel), the share of such
// pixels over a box of kOffsetCheckRadius, at full resolution (bilinear). A sheen that the offsets
// cancel lets the views agree better; offsets that a map error put there (on texture that is
// locally a ramp, above) leave them agreeing worse, since each view keeps e (g - mean g). The first
// and second half-resolution maps of the coarse texture at 256 px score 5.97 and 24.12 %. Without
// the tolerance: development means 2.190 -> 1.707 % at 128 px and 3.191 -> 1.718 % at 256 (the
// coarse texture 12.52 -> 2.18 and 32.74 -> 5.91 %), the glossy unevenly lit slants 3.25 -> 5.77 %
// at 128 the most it cost. The tolerance, in the residual's own scale (a fixed one helped at 128 px
// and hurt at 256, where the residuals are smaller), lets a pixel whose residual barely moved keep
// its offsets: 1.707 -> 1.620 % at 128 px and 1.718 -> 1.696 % at 256 (the glossy unevenly lit
// slants 5.77 -> 4.25 %, the coarse texture at 256 5.91 -> 4.97 %); 0.1, 0.3, 1 and 2 gave 1.703 /
// 1.746, 1.600 / 1.710, 1.645 / 1.693 and 1.655 / 1.692 %. Other radii and soft shares measured
// worse.
constexpr int kOffsetCheckRadius = 2;

constexpr double kOffsetCheckTolerance = 0.6;

}  // namespace

std::vector<float> offsetsKept(const Residual& before, const std::vector<float>& after, int halfWidth, int halfHeight,
                               int width, int height) {
  const std::size_t n = before.perPixel.size();
  std::vector<float> agree(n), share(n), kept(std::size_t(width) * height);
  const double tolerance = kOffsetCheckTolerance * before.median;
  for (std::size_t i = 0; i < n; ++i) agree[i] = after[i] <= before.perPixel[i] + tolerance ? 1.0f : 0.0f;
  boxFilter(agree.data(), share.data(), halfWidth, halfHeight, kOffsetCheckRadius);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      kept[std::size_t(y) * width + x] = float(sampleHalfResolution(share.data(), halfWidth, halfHeight, x, y));
  return kept;
}

}  // namespace lfcam::edof
