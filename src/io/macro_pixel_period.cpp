#include "io/macro_pixel_period.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace lfcam::io {

namespace {

// The best period must stand out (F) and explain a good share of the profile's variance, or it is
// not told apart from the texture of the scene. Lenslet images (synthetic, and the HCI and Lytro
// views rearranged) reach F > 60 with more than half explained, most F > 1000 and 99%; plain
// photographs stay below F = 10, or below 30% explained (the 8-pixel blocks of a JPEG-compressed
// picture come closest).
constexpr double kMinimumF = 20.0;
constexpr double kMinimumExplained = 0.4;
constexpr int kMaximumPeriod = 256;

// Mean |I(i + 1) - I(i)| over the other axis and all channels, for i in [0, n - 1).
std::vector<double> differenceProfile(const Image& image, bool alongX) {
  const int n = alongX ? image.width() : image.height();
  const int across = alongX ? image.height() : image.width();
  const int step = std::max(1, across / 1024);  // a thousand lines are plenty
  std::vector<double> profile(std::size_t(std::max(n - 1, 0)), 0.0);
  for (int c = 0; c < image.channels(); ++c)
    for (int line = 0; line < across; line += step)
      for (int i = 0; i + 1 < n; ++i) {
        const float a = alongX ? image.at(i, line, c) : image.at(line, i, c);
        const float b = alongX ? image.at(i + 1, line, c) : image.at(line, i + 1, c);
        if (std::isfinite(a) && std::isfinite(b)) profile[std::size_t(i)] += std::abs(double(b) - double(a));
      }
  return profile;
}

// The profile divided by its mean over a sliding window of one period: the pattern of the
// macro-pixels stays, while slow changes of the scene's gradient along the axis go.
std::vector<double> normalised(const std::vector<double>& profile, int k) {
  const std::size_t count = profile.size();
  std::vector<double> prefix(count + 1, 0.0);
  for (std::size_t i = 0; i < count; ++i) prefix[i + 1] = prefix[i] + profile[i];
  std::vector<double> out(count);
  for (std::size_t i = 0; i < count; ++i) {
    std::size_t begin = i >= std::size_t(k / 2) ? i - std::size_t(k / 2) : 0;
    begin = std::min(begin, count - std::size_t(k));
    const double mean = (prefix[begin + std::size_t(k)] - prefix[begin]) / k;
    out[i] = mean > 0 ? profile[i] / mean : 1.0;
  }
  return out;
}

struct Fold {
  double f = 0;          // between-phase over within-phase variance, per degree of freedom
  double explained = 0;  // share of the profile's variance that the phases explain
};

// The profile folded with period k: how much of it the phase i mod k explains.
Fold fold(const std::vector<double>& profile, int k) {
  const std::size_t count = profile.size();
  std::vector<double> sum(std::size_t(k), 0.0);
  std::vector<std::size_t> members(std::size_t(k), 0);
  double total = 0;
  for (std::size_t i = 0; i < count; ++i) {
    sum[i % std::size_t(k)] += profile[i];
    ++members[i % std::size_t(k)];
    total += profile[i];
  }
  const double mean = total / double(count);
  double between = 0, within = 0;
  for (int phase = 0; phase < k; ++phase) {
    const double phaseMean = sum[std::size_t(phase)] / double(members[std::size_t(phase)]);
    between += double(members[std::size_t(phase)]) * (phaseMean - mean) * (phaseMean - mean);
  }
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t phase = i % std::size_t(k);
    const double deviation = profile[i] - sum[phase] / double(members[phase]);
    within += deviation * deviation;
  }
  Fold result;
  result.explained = between + within > 0 ? between / (between + within) : 0;
  // Relative floor: a profile that repeats exactly has no variance within phases.
  const double floor = 1e-12 * (mean * mean + 1e-30);
  result.f = (between / double(k - 1)) / std::max(within / double(count - std::size_t(k)), floor);
  return result;
}

}  // namespace

std::optional<int> estimateMacroPixelPeriod(const Image& image, bool alongX) {
  const int n = alongX ? image.width() : image.height();
  const std::vector<double> profile = differenceProfile(image, alongX);
  Fold best;
  int period = 0;
  // Candidates divide the size and leave at least four macro-pixels to compare.
  for (int k = 2; k <= std::min(kMaximumPeriod, n / 4); ++k) {
    if (n % k != 0) continue;
    const Fold candidate = fold(normalised(profile, k), k);
    if (candidate.f > best.f * 1.0001) best = candidate, period = k;  // ties go to the smaller period
  }
  if (period == 0 || best.f < kMinimumF || best.explained < kMinimumExplained) return std::nullopt;
  return period;
}

}  // namespace lfcam::io
