// A first lattice from the autocorrelation of the image's central part: its peaks sit at the
// lattice vectors, whatever the packing, pitch or rotation.
#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>

#include <fftw3.h>

#include "calibrate/calibrate_internal.hpp"
#include "core/fftw_planner.hpp"
#include "core/parabola.hpp"

namespace lfcam::calibrate_detail {

namespace {

struct Peak {
  double x = 0, y = 0;  // lag, pixels
  double value = 0;     // normalised autocorrelation
};

// Lagrange-Gauss reduction: the shortest basis of the 2D lattice spanned by a and b.
void reduceBasis(std::array<double, 2>& a, std::array<double, 2>& b) {
  auto dot = [](const std::array<double, 2>& p, const std::array<double, 2>& q) { return p[0] * q[0] + p[1] * q[1]; };
  for (int guard = 0; guard < 32; ++guard) {
    if (dot(b, b) < dot(a, a)) std::swap(a, b);
    const double m = std::round(dot(a, b) / dot(a, a));
    if (m == 0) return;
    b = {b[0] - m * a[0], b[1] - m * a[1]};
  }
}

}  // namespace

Result<Lattice> latticeFromAutocorrelation(const Image& prepared, const std::string& where, double minPeak) {
  const int size = std::min({prepared.width(), prepared.height(), 1024}) & ~1;
  if (size < 32) return makeError(ErrorCode::Format, where + ": too small to find a microlens lattice in");
  const int x0 = (prepared.width() - size) / 2, y0 = (prepared.height() - size) / 2;
  const int half = size / 2 + 1;
  std::unique_ptr<float, fftw::Free> real(static_cast<float*>(fftwf_malloc(sizeof(float) * size * size)));
  std::unique_ptr<fftwf_complex, fftw::Free> spectrum(
      static_cast<fftwf_complex*>(fftwf_malloc(sizeof(fftwf_complex) * size * half)));
  fftwf_plan forward, inverse;
  {
    std::lock_guard<std::mutex> lock(fftw::plannerMutex());
    forward = fftwf_plan_dft_r2c_2d(size, size, real.get(), spectrum.get(), FFTW_ESTIMATE);
    inverse = fftwf_plan_dft_c2r_2d(size, size, spectrum.get(), real.get(), FFTW_ESTIMATE);
  }
  // Mean removed, Hann window: the crop's edges would otherwise add a cross to the spectrum.
  double mean = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) mean += prepared.at(x0 + x, y0 + y, 0);
  mean /= double(size) * size;
  std::vector<float> window(size);
  for (int k = 0; k < size; ++k) window[k] = float(0.5 - 0.5 * std::cos(2 * M_PI * (k + 0.5) / size));
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      real.get()[y * size + x] = float(prepared.at(x0 + x, y0 + y, 0) - mean) * window[x] * window[y];
  fftwf_execute(forward);
  for (int k = 0; k < size * half; ++k) {
    fftwf_complex& c = spectrum.get()[k];
    c[0] = c[0] * c[0] + c[1] * c[1];
    c[1] = 0;
  }
  fftwf_execute(inverse);
  {
    std::lock_guard<std::mutex> lock(fftw::plannerMutex());
    fftwf_destroy_plan(forward);
    fftwf_destroy_plan(inverse);
  }
  const float* ac = real.get();
  const double zero = ac[0];
  if (!(zero > 0)) return makeError(ErrorCode::Format, where + ": the image is flat: no microlens lattice in it");
  auto at = [&](int dx, int dy) { return ac[((dy + size) % size) * size + (dx + size) % size] / zero; };

  // Peaks: local maxima over 5x5, separated from the origin by a valley (the value half-way is
  // lower), in one half-plane (the autocorrelation is symmetric).
  const int reach = size / 4;
  std::vector<Peak> peaks;
  for (int dy = 0; dy <= reach; ++dy)
    for (int dx = -reach; dx <= reach; ++dx) {
      if (dy == 0 && dx <= 0) continue;
      if (dx * dx + dy * dy < 3.5 * 3.5) continue;
      const double v = at(dx, dy);
      bool isMax = true;
      for (int ey = -2; ey <= 2 && isMax; ++ey)
        for (int ex = -2; ex <= 2; ++ex)
          if ((ex || ey) && at(dx + ex, dy + ey) >= v) {
            isMax = false;
            break;
          }
      if (!isMax) continue;
      const double valley = at(int(std::lround(dx / 2.0)), int(std::lround(dy / 2.0)));
      if (v - valley < 0.02) continue;
      // Sub-pixel position along each axis: the vertex of the parabola through the peak, as the
      // minimum of the negated samples.
      peaks.push_back({dx + parabolaVertex(-at(dx - 1, dy), -v, -at(dx + 1, dy)),
                       dy + parabolaVertex(-at(dx, dy - 1), -v, -at(dx, dy + 1)), v});
    }
  if (peaks.empty()) return makeError(ErrorCode::Format, where + ": no periodic microlens pattern found");
  double strongest = 0;
  for (const Peak& p : peaks) strongest = std::max(strongest, p.value);
  // The lattice vectors nearest the origin are all about as strong as the strongest peak (the
  // caller's minPeak: see calibrate.cpp).
  std::erase_if(peaks, [&](const Peak& p) { return p.value < minPeak * strongest; });
  std::sort(peaks.begin(), peaks.end(),
            [](const Peak& a, const Peak& b) { return std::hypot(a.x, a.y) < std::hypot(b.x, b.y); });
  std::array<double, 2> a{peaks[0].x, peaks[0].y}, b{0, 0};
  bool found = false;
  for (std::size_t k = 1; k < peaks.size() && !found; ++k) {
    const double cross = a[0] * peaks[k].y - a[1] * peaks[k].x;
    if (std::abs(cross) > 0.5 * std::hypot(a[0], a[1]) * std::hypot(peaks[k].x, peaks[k].y)) {
      b = {peaks[k].x, peaks[k].y};
      found = true;
    }
  }
  if (!found)
    return makeError(ErrorCode::Format, where + ": found only one direction of periodicity, not a microlens lattice");
  reduceBasis(a, b);
  const double la = std::hypot(a[0], a[1]), lb = std::hypot(b[0], b[1]);
  const double cosine = (a[0] * b[0] + a[1] * b[1]) / (la * lb);
  Lattice lattice;
  // A reduced basis of a hexagonal lattice: equal lengths at 60 or 120 degrees.
  lattice.packing =
      std::abs(la - lb) < 0.1 * la && std::abs(std::abs(cosine) - 0.5) < 0.15 ? Packing::Hexagonal : Packing::Square;
  // The row direction: the shortest lattice vector closest to the x axis.
  std::vector<std::array<double, 2>> candidates = {a, b};
  if (lattice.packing == Packing::Hexagonal)
    candidates.push_back(cosine > 0 ? std::array<double, 2>{a[0] - b[0], a[1] - b[1]}
                                    : std::array<double, 2>{a[0] + b[0], a[1] + b[1]});
  double best = INFINITY;
  std::array<double, 2> row{};
  for (auto v : candidates) {
    if (v[0] < 0) v = {-v[0], -v[1]};
    const double angle = std::abs(std::atan2(v[1], v[0]));
    if (angle < best) {
      best = angle;
      row = v;
    }
  }
  lattice.pitchX = std::hypot(row[0], row[1]);
  lattice.theta = std::atan2(row[1], row[0]);
  lattice.pitchY = std::abs(a[0] * b[1] - a[1] * b[0]) / lattice.pitchX;  // cell area / pitchX
  return lattice;
}

}  // namespace lfcam::calibrate_detail
