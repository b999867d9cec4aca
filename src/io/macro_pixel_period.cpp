#include "io/macro_pixel_period.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <span>

#include "core/power_spectrum.hpp"

namespace lfcam::io {

namespace {

// Two pixels repeat in many photographs (Bayer demosaicking, subsampled chroma): give such a
// light field's views per lens.
constexpr int kMinimumPeriod = 3;
constexpr int kMaximumPeriod = 256;
constexpr int kMinimumMacroPixels = 4;
// Scores are the teeth's mean excess power in units of the background's power per bin. In the
// tests' lenslet images (synthetic, simulated, Lytro and microscope frames, also mostly dark and
// noisy) the deciding profile reaches 25 to millions with 39% to all of the power explained; real
// photographs and their JPEGs stay below 16 and 25% (subsampled chroma and 8-pixel blocks).
constexpr double kMinimumScore = 20;
constexpr double kMinimumShare = 0.3;
constexpr double kPlausibleScore = 8;
// A pattern under part of the image broadens its peaks evenly about the harmonics (within 0.25
// bins in the frames above); a pitch near, not at, a whole number (a raw frame) puts them aside.
constexpr double kMaximumOffset = 0.5;
// A multiple's own harmonics (those of no smaller period) must carry this share of the period's
// score: a pattern whose fundamental is weaker than its harmonics is found at a divisor first.
constexpr double kExtensionScore = 0.25;
// Sub-blocks of the folded intensity are one shape at different brightnesses when each correlates
// this well with their sum and has at least a tenth of the largest one's amplitude.
constexpr double kSameShapeCorrelation = 0.9;
constexpr double kSameShapeEnergy = 0.01;
constexpr std::size_t kMostPlausible = 4;

struct Profile {
  std::vector<double> values;
  std::vector<double> spectrum;
};

// Sums over the other axis and the channels of the intensity and of |I(i + 1) - I(i)|, i along
// the axis (the last difference, past the image's edge, is the mean of the others). Row by row,
// for the cache.
std::pair<Profile, Profile> profilesOf(const Image& image, bool alongX) {
  const int n = alongX ? image.width() : image.height();
  std::vector<double> intensity(std::size_t(n), 0.0), difference(std::size_t(n), 0.0);
  for (int c = 0; c < image.channels(); ++c)
    for (int y = 0; y < image.height(); ++y) {
      const float* row = image.row(y, c);
      if (alongX) {
        for (int x = 0; x < n; ++x)
          if (std::isfinite(row[x])) intensity[std::size_t(x)] += row[x];
        for (int x = 0; x + 1 < n; ++x)
          if (std::isfinite(row[x]) && std::isfinite(row[x + 1]))
            difference[std::size_t(x)] += std::abs(double(row[x + 1]) - double(row[x]));
        continue;
      }
      double sum = 0, changes = 0;
      const float* next = y + 1 < n ? image.row(y + 1, c) : nullptr;
      for (int x = 0; x < image.width(); ++x) {
        if (!std::isfinite(row[x])) continue;
        sum += row[x];
        if (next && std::isfinite(next[x])) changes += std::abs(double(next[x]) - double(row[x]));
      }
      intensity[std::size_t(y)] += sum;
      difference[std::size_t(y)] += changes;
    }
  double mean = 0;
  for (int i = 0; i + 1 < n; ++i) mean += difference[std::size_t(i)];
  if (n > 1) difference[std::size_t(n - 1)] = mean / (n - 1);
  std::pair<Profile, Profile> result{{std::move(intensity), {}}, {std::move(difference), {}}};
  result.first.spectrum = powerSpectrum(result.first.values);
  result.second.spectrum = powerSpectrum(result.second.values);
  return result;
}

// The harmonics of period k in the spectrum of n points fall every `spacing` = n / k bins; each
// tooth spans `halfWidth` bins either side, as a pattern under part of the image has broad peaks.
struct Comb {
  int spacing, halfWidth;
  Comb(int n, int k) : spacing(n / k), halfWidth(std::clamp((n / k - 2) / 4, 0, 3)) {}
  bool inTooth(int f) const { return std::min(f % spacing, spacing - f % spacing) <= halfWidth; }
  int firstBin() const { return std::max(1, spacing / 2); }  // below: the scene's slow changes
};

// Mean power per bin between the teeth (a floor keeps exact patterns finite).
double background(const std::vector<double>& spectrum, const Comb& comb) {
  const int last = int(spectrum.size()) - 1;
  double sum = 0, peak = 0;
  int bins = 0;
  for (int f = comb.firstBin(); f <= last; ++f) {
    peak = std::max(peak, spectrum[std::size_t(f)]);
    if (!comb.inTooth(f)) sum += spectrum[std::size_t(f)], ++bins;
  }
  return std::max(bins > 0 ? sum / bins : peak, 1e-12 * peak + 1e-300);
}

struct Tooth {
  double excess = 0;  // power above the background
  double offset = 0;  // of the power above the background from the harmonic, bins (its centroid)
};

Tooth tooth(const std::vector<double>& spectrum, const Comb& comb, int m, double floor) {
  const int last = int(spectrum.size()) - 1;
  Tooth result;
  double above = 0, moment = 0;
  for (int f = m * comb.spacing - comb.halfWidth; f <= std::min(m * comb.spacing + comb.halfWidth, last); ++f) {
    const double excess = spectrum[std::size_t(f)] - floor;
    result.excess += excess;
    above += std::max(0.0, excess);
    moment += std::max(0.0, excess) * (f - m * comb.spacing);
  }
  result.offset = above > 0 ? moment / above : 0;
  return result;
}

struct Score {
  double score = 0;        // mean excess per tooth over the background per bin
  double share = 0;        // the teeth's excess over all the power from the comb's first bin up
  double offset = 0;       // of the teeth's peaks from their harmonics, bins: near 0 for a whole period
  bool harmonics = false;  // two teeth stand out (the one there is, for periods 3 and 4): not a sinusoid
};

// The comb of period k; with `withinDivisor` > 1, only the harmonics that period k / withinDivisor
// lacks (m not a multiple of withinDivisor).
Score combScore(const Profile& profile, int k, int withinDivisor = 1) {
  const int n = int(profile.values.size());
  const Comb comb(n, k);
  const double floor = background(profile.spectrum, comb);
  double excess = 0, weightedOffset = 0, weights = 0;
  int teeth = 0, strongTeeth = 0;
  for (int m = 1; m * comb.spacing < int(profile.spectrum.size()); ++m) {
    if (withinDivisor > 1 && m % withinDivisor == 0) continue;
    const Tooth t = tooth(profile.spectrum, comb, m, floor);
    excess += t.excess;
    if (t.excess >= kPlausibleScore * floor) ++strongTeeth;
    weightedOffset += std::max(0.0, t.excess) * std::abs(t.offset);
    weights += std::max(0.0, t.excess);
    ++teeth;
  }
  double total = 0;
  for (std::size_t f = std::size_t(comb.firstBin()); f < profile.spectrum.size(); ++f) total += profile.spectrum[f];
  Score result;
  result.score = teeth > 0 ? excess / teeth / floor : 0;
  result.share = total > 0 ? excess / total : 0;
  result.offset = weights > 0 ? weightedOffset / weights : 0;
  result.harmonics = std::min(strongTeeth, 2) == std::min(teeth, 2);
  return result;
}

// Whether the intensity folded with period k splits into sub-blocks of d pixels that are one shape
// at different brightnesses over a common level (or all flat): lenses of a scene textured at k / d
// lenses, not a pattern of k pixels.
bool lensesDifferOnlyInBrightness(const std::vector<double>& intensity, int k, int d) {
  std::vector<double> folded(std::size_t(k), 0.0);
  const std::size_t blocks = intensity.size() / std::size_t(k);
  for (std::size_t i = 0; i < blocks * std::size_t(k); ++i) folded[i % std::size_t(k)] += intensity[i];
  double mean = 0, total = 0;
  for (double value : folded) mean += value / k;
  for (double value : folded) total += (value - mean) * (value - mean);
  // Each sub-block less its mean; their sum is the shape they would share.
  const int parts = k / d;
  std::vector<double> centred(folded.size()), shape(std::size_t(d), 0.0), energy(std::size_t(parts), 0.0);
  for (int part = 0; part < parts; ++part) {
    const auto begin = folded.begin() + part * d;
    const double partMean = std::accumulate(begin, begin + d, 0.0) / d;
    for (int u = 0; u < d; ++u) {
      const std::size_t i = std::size_t(part * d + u);
      centred[i] = folded[i] - partMean;
      shape[std::size_t(u)] += centred[i];
      energy[std::size_t(part)] += centred[i] * centred[i];
    }
  }
  const double within = std::accumulate(energy.begin(), energy.end(), 0.0);
  if (within <= kSameShapeEnergy * total) return true;  // flat lenses: only their brightness varies
  const double largest = *std::max_element(energy.begin(), energy.end());
  const double shapeEnergy = std::inner_product(shape.begin(), shape.end(), shape.begin(), 0.0);
  for (int part = 0; part < parts; ++part) {
    if (energy[std::size_t(part)] < kSameShapeEnergy * largest) return false;
    const double dot = std::inner_product(shape.begin(), shape.end(), centred.begin() + part * d, 0.0);
    if (dot < kSameShapeCorrelation * std::sqrt(energy[std::size_t(part)] * shapeEnergy)) return false;
  }
  return true;
}

struct Finding {
  int period = 0;
  Score score;
  bool sure() const {
    return period > 0 && score.score >= kMinimumScore && score.share >= kMinimumShare &&
           score.offset <= kMaximumOffset && score.harmonics;
  }
};

Finding findPeriod(const Profile& profile, const std::vector<int>& candidates, std::map<int, double>& plausible,
                   bool reduceByBrightness) {
  Finding best;
  best.score.score = -1e300;
  for (int k : candidates) {
    const Score score = combScore(profile, k);
    if (score.score >= kPlausibleScore) plausible[k] = std::max(plausible[k], score.score);
    if (score.score > best.score.score) best = {k, score};
  }
  // Extended to the first multiple whose own harmonics stand out, as long as one does.
  for (bool extended = true; extended;) {
    extended = false;
    const double enough = std::max(kPlausibleScore, kExtensionScore * best.score.score);
    for (int k : candidates)
      if (k > best.period && k % best.period == 0 && combScore(profile, k, k / best.period).score >= enough) {
        best = {k, combScore(profile, k)};
        extended = true;
        break;
      }
  }
  // The evidence stays that of the pattern found; only its period is the lens's.
  if (reduceByBrightness)
    for (int d : candidates)
      if (d < best.period && best.period % d == 0 && lensesDifferOnlyInBrightness(profile.values, best.period, d)) {
        best.period = d;
        break;
      }
  return best;
}

// The most plausible periods, leaving out multiples of likelier ones.
std::vector<int> mostPlausible(const std::map<int, double>& scores) {
  std::vector<std::pair<double, int>> ranked;
  for (const auto& [k, score] : scores) ranked.emplace_back(-score, k);
  std::sort(ranked.begin(), ranked.end());
  std::vector<int> periods;
  for (const auto& entry : ranked) {
    const int k = entry.second;  // a plain variable: clang 14 cannot capture a structured binding
    if (std::any_of(periods.begin(), periods.end(), [k](int p) { return k % p == 0; })) continue;
    periods.push_back(k);
    if (periods.size() == kMostPlausible) break;
  }
  return periods;
}

}  // namespace

MacroPixelPeriod estimateMacroPixelPeriod(const Image& image, bool alongX) {
  const int n = alongX ? image.width() : image.height();
  std::vector<int> candidates;
  for (int k = kMinimumPeriod; k <= std::min(kMaximumPeriod, n / kMinimumMacroPixels); ++k)
    if (n % k == 0) candidates.push_back(k);
  if (candidates.empty()) return {};
  const auto [intensity, difference] = profilesOf(image, alongX);
  std::map<int, double> plausible;
  const Finding fromIntensity = findPeriod(intensity, candidates, plausible, true);
  const Finding fromDifference = findPeriod(difference, candidates, plausible, false);

  MacroPixelPeriod result;
  if (fromIntensity.sure() && fromDifference.sure()) {
    const int a = std::min(fromIntensity.period, fromDifference.period);
    const int b = std::max(fromIntensity.period, fromDifference.period);
    // Agreeing, or one of them a multiple of the other (a scene textured at the lenses' scale).
    if (b % a == 0) {
      result.period = a;
    } else {
      const bool intensityLikelier = fromIntensity.score.score >= fromDifference.score.score;
      result.plausible = {intensityLikelier ? fromIntensity.period : fromDifference.period,
                          intensityLikelier ? fromDifference.period : fromIntensity.period};
    }
  } else if (fromIntensity.sure()) {
    result.period = fromIntensity.period;
  } else if (fromDifference.sure()) {
    result.period = fromDifference.period;
  } else {
    result.plausible = mostPlausible(plausible);
  }
  return result;
}

}  // namespace lfcam::io
