// Averages, signal-to-noise against a noise-free standard, line fits, a focus measure.
#include <cmath>

#include "lfcam/analysis/analysis.hpp"

namespace lfcam {

Result<Image> averageImages(const std::vector<const Image*>& images) {
  if (images.empty()) return makeError(ErrorCode::Usage, "average: no images");
  const Image& first = *images.front();
  std::vector<double> sum(first.pixels().size(), 0.0);
  for (const Image* image : images) {
    if (image->width() != first.width() || image->height() != first.height() || image->channels() != first.channels())
      return makeError(ErrorCode::Usage, "average: the images differ in size");
    const auto pixels = image->pixels();
    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += pixels[i];
  }
  Image mean(first.width(), first.height(), first.channels());
  auto out = mean.pixels();
  for (std::size_t i = 0; i < sum.size(); ++i) out[i] = float(sum[i] / double(images.size()));
  return mean;
}

Result<SignalToNoise> signalToNoise(const Image& frame, const Image& standard, const Image* mask) {
  if (frame.width() != standard.width() || frame.height() != standard.height() || frame.empty())
    return makeError(ErrorCode::Usage, "signal to noise: the frame and the standard differ in size");
  if (mask && (mask->width() != frame.width() || mask->height() != frame.height()))
    return makeError(ErrorCode::Usage, "signal to noise: the mask differs in size");
  double signal = 0, squared = 0;
  std::size_t count = 0;
  for (int y = 0; y < frame.height(); ++y)
    for (int x = 0; x < frame.width(); ++x) {
      if (mask && !(mask->at(x, y, 0) > 0)) continue;
      const double d = double(frame.at(x, y, 0)) - standard.at(x, y, 0);
      signal += standard.at(x, y, 0);
      squared += d * d;
      ++count;
    }
  if (count == 0) return makeError(ErrorCode::Usage, "signal to noise: the mask selects no pixel");
  SignalToNoise result;
  result.signal = signal / double(count);
  result.noise = std::sqrt(squared / double(count));
  result.snr = result.noise > 0 ? result.signal / result.noise : 0;
  return result;
}

Result<LinearFit> fitLine(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size() || x.size() < 2) return makeError(ErrorCode::Usage, "line fit: needs two or more points");
  const double n = double(x.size());
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < x.size(); ++i) mx += x[i], my += y[i];
  mx /= n, my /= n;
  double sxx = 0, sxy = 0, syy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
    syy += (y[i] - my) * (y[i] - my);
  }
  if (!(sxx > 0)) return makeError(ErrorCode::Usage, "line fit: all x are equal");
  LinearFit fit;
  fit.slope = sxy / sxx;
  fit.intercept = my - fit.slope * mx;
  double residual = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double e = y[i] - (fit.slope * x[i] + fit.intercept);
    residual += e * e;
  }
  fit.r2 = syy > 0 ? 1 - residual / syy : 1;
  return fit;
}

double gradientEnergy(const Image& photo) {
  if (photo.width() < 2 || photo.height() < 2) return 0;
  double sum = 0;
  for (int y = 0; y + 1 < photo.height(); ++y)
    for (int x = 0; x + 1 < photo.width(); ++x) {
      const double gx = double(photo.at(x + 1, y, 0)) - photo.at(x, y, 0);
      const double gy = double(photo.at(x, y + 1, 0)) - photo.at(x, y, 0);
      sum += gx * gx + gy * gy;
    }
  return sum / (double(photo.width() - 1) * (photo.height() - 1));
}

}  // namespace lfcam
