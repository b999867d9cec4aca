// Steps of the lattice calibration (src/calibrate/), shared by its source files.
#pragma once

#include <array>
#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "lfcam/calibrate/calibrate.hpp"

namespace lfcam::calibrate_detail {

// The lattice in its own indices: microlens (k, n) at
//   o + R(theta) ((k + shift(n)) pitchX, n pitchY),  shift(n) = 1/2 for odd n when hexagonal.
struct Lattice {
  Packing packing = Packing::Square;
  double ox = 0, oy = 0, theta = 0, pitchX = 0, pitchY = 0;

  double shift(int n) const { return packing == Packing::Hexagonal && (n & 1) ? 0.5 : 0.0; }
  std::array<double, 2> centre(int k, int n) const;
  // Centre-to-centre distance of nearest neighbours.
  double neighbourDistance() const;
  // Pixel offsets from a microlens to its nearest neighbours (6 when hexagonal, 8 when square).
  std::vector<std::array<double, 2>> neighbourOffsets() const;
};

// A measured centre with its lattice indices.
struct Sample {
  int k = 0, n = 0;
  double x = 0, y = 0;
};

struct LatticeFit {
  Lattice lattice;
  std::vector<char> inlier;      // per sample
  std::vector<double> residual;  // per sample, pixels
  int used = 0;
  double rms = 0, max = 0;  // over the inliers
};

// Least squares (Gauss-Newton on origin, rotation, pitchX, pitchY) with iterative rejection of
// samples whose residual exceeds 4 sigma (sigma from the median residual). Starts at `start`.
LatticeFit fitLattice(const std::vector<Sample>& samples, const Lattice& start);

// Fits grid.warp to the inlier centres' residuals against the lattice (grid_warp.cpp) and
// updates their residuals and grid.fit to the warped grid.
void fitGridWarp(LensletGrid& grid, std::vector<DetectedCentre>& centres);

// A first lattice (packing, pitches, rotation; no origin) from the autocorrelation of the central
// part of a prepared image. Fails when no two independent periodic peaks are found. minPeak:
// the share of the strongest peak a lattice vector's peak must reach.
Result<Lattice> latticeFromAutocorrelation(const Image& prepared, const std::string& where, double minPeak = 0.7);

struct CentreEstimate {
  double x = 0, y = 0;
  double contrast = 0;  // max - min of the image in the window
  bool ok = false;      // converged with the window inside the image
};

// Iterated centroid of max(image - level, 0) over a soft-edged disc of `radius` around the
// estimate (level: 10% of the way from the first window's min to its max): converges to the
// centre of a bright spot or disc from a guess a quarter of its size off. relax multiplies each
// step (a flat disc's centroid moves only half-way). Not ok when the window leaves the image or
// the steps do not settle.
// Stops when a step is below `tolerance` pixels.
CentreEstimate refineCentre(const Image& image, double x, double y, double radius, int iterations, double relax = 1.0,
                            double tolerance = 1e-3);
// The same with every pixel of the window through the weight's formula (the reference).
CentreEstimate refineCentreReference(const Image& image, double x, double y, double radius, int iterations,
                                     double relax = 1.0, double tolerance = 1e-3);

// The centre of symmetry of `image` near (x, y): Gauss-Newton on the sum over offsets d within
// `radius` of [I(c + d) - I(c - d) - (g . e(d))(I(c + d) + I(c - d))]^2 over the centre c and a
// tilt g, bilinear samples, where e(d) is d taken from the nearest of c and c + `neighbours`: each
// microlens image in the window carries the ramp about its own centre. Unbiased for any centrally
// symmetric microlens image, whatever its shape, also under a linear ramp of brightness across
// each image (vignetting off the axis), with its neighbours' images inside the window.
CentreEstimate refineSymmetric(const Image& image, double x, double y, double radius, int iterations,
                               const std::vector<std::array<double, 2>>& neighbours = {});
// The same with every sample interpolated on its own (the reference of the fast path, which
// resamples the window once per step: symmetric_centre.cpp).
CentreEstimate refineSymmetricReference(const Image& image, double x, double y, double radius, int iterations,
                                        const std::vector<std::array<double, 2>>& neighbours = {});

// Preparation (prepare.cpp): one channel (channels averaged), black level off, a mosaic's 2x2
// phases scaled to their common mean, a 3x3 median (not for pinhole targets, whose spots may be a
// pixel across), for a mosaic the [1 2 1] binomial along x then y, and, when `smoothed`, the [1 2 1]
// along y then x that takes the remaining noise off the centre estimates. All centrally symmetric
// with borders clamped to the whole image, so a region is exactly that part of the whole.
struct PhaseGains {
  std::array<float, 4> gain{1, 1, 1, 1};  // phase 2 (y & 1) + (x & 1); all 1 without a mosaic
};
PhaseGains phaseGains(const Image& image, const CalibrationOptions& options);
// Columns [x0, x1), rows [y0, y1) of the prepared image: one pass over the rows, nothing else kept.
Image prepareRegion(const Image& image, const CalibrationOptions& options, const PhaseGains& gains, int x0, int y0,
                    int x1, int y1, bool smoothed);
// The smoothing alone of a prepared image.
Image smoothBinomial(const Image& work);
// The plain reference: one whole-image pass per step.
Image prepareReference(const Image& image, const CalibrationOptions& options, bool smoothed);

// median3x3 (calibrate.hpp), plainly per pixel: the reference of the fast kernel.
Image median3x3Reference(const Image& image);
// One row of the 3x3 median (median3x3.cpp): out[x] for x in [x0, x1) of rows `width` wide;
// above or below is null outside the image, where the window is clipped.
void median3x3Row(const float* above, const float* row, const float* below, int width, int x0, int x1, float* out);

// The JSON in a file; errors name it. expected: what the file should be, for the message.
Result<nlohmann::json> readJsonFile(const std::filesystem::path& path, const char* expected);

}  // namespace lfcam::calibrate_detail
