// analysis: the transfer function against a direct DFT, the 75% cutoff, SNR and line fits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "analysis/references.hpp"
#include "lfcam/analysis/analysis.hpp"

namespace lfcam {
namespace {

Image disc(int size, double radius) {
  Image image(size, size, 1);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) image.at(x, y, 0) = std::hypot(x - size / 2, y - size / 2) <= radius ? 1.0f : 0.0f;
  return image;
}

TEST(Analysis, TransferFunctionMatchesTheDirectDft) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> value(0, 1);
  for (auto [w, h] : {std::pair{8, 8}, std::pair{9, 6}, std::pair{13, 7}}) {
    Image image(w, h, 1);
    for (float& v : image.pixels()) v = value(random);
    auto fast = transferFunction(image), reference = transferFunctionReference(image);
    ASSERT_TRUE(fast && reference);
    for (std::size_t i = 0; i < fast->pixels().size(); ++i)
      EXPECT_NEAR(fast->pixels()[i], reference->pixels()[i], 1e-4) << w << "x" << h << " at " << i;
    EXPECT_FLOAT_EQ(fast->at(w / 2, h / 2, 0), 1.0f);
  }
}

TEST(Analysis, ZeroPaddedTransferFunctionMatchesTheDirectDft) {
  std::mt19937 random(11);
  std::uniform_real_distribution<float> value(0, 1);
  Image image(7, 5, 1);
  for (float& v : image.pixels()) v = value(random);
  auto fast = transferFunction(image, 3), reference = transferFunctionReference(image, 3);
  ASSERT_TRUE(fast && reference);
  ASSERT_EQ(fast->width(), 21);
  ASSERT_EQ(fast->height(), 15);
  for (std::size_t i = 0; i < fast->pixels().size(); ++i) EXPECT_NEAR(fast->pixels()[i], reference->pixels()[i], 1e-4);
  EXPECT_FALSE(transferFunction(image, 0));
}

// A Gaussian blur of sigma pixels has |H(f)|^2 = exp(-4 pi^2 sigma^2 |f|^2), whose disc of radius
// sqrt(ln 4) / (2 pi sigma) holds 75% of the energy.
Image gaussian(int size, double sigma) {
  Image image(size, size, 1);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      image.at(x, y, 0) =
          float(std::exp(-(std::pow(x - size / 2, 2) + std::pow(y - size / 2, 2)) / (2 * sigma * sigma)));
  return image;
}
double gaussianCutoff(double sigma) { return std::sqrt(std::log(4.0)) / (2 * 3.14159265358979 * sigma); }

TEST(Analysis, CutoffOfAGaussianIsReadBetweenTheBins) {
  // On a 32-pixel photograph the bins are 1/32 = 0.031 cycles per pixel apart; the zero-padded,
  // interpolated cutoff lands within 1% of the exact one where the bins alone are off by more.
  double worstBins = 0;
  for (double sigma : {1.5, 1.8, 2.1, 2.5, 3.0}) {
    const Image blur = gaussian(32, sigma);
    auto padded = transferFunction(blur, 8), bins = transferFunction(blur);
    ASSERT_TRUE(padded && bins);
    const double exact = gaussianCutoff(sigma);
    EXPECT_NEAR(cutoffFrequency(*padded) / exact, 1.0, 0.01) << "sigma " << sigma;
    worstBins = std::max(worstBins, std::abs(cutoffFrequency(*bins) / exact - 1));
  }
  EXPECT_GT(worstBins, 0.02);
  // And it follows the blur continuously: a wider blur, a strictly lower cutoff, in small steps.
  double previous = 1;
  for (double sigma = 2.0; sigma <= 2.3; sigma += 0.02) {
    auto padded = transferFunction(gaussian(32, sigma), 8);
    ASSERT_TRUE(padded);
    const double cutoff = cutoffFrequency(*padded);
    EXPECT_LT(cutoff, previous) << "sigma " << sigma;
    previous = cutoff;
  }
}

TEST(Analysis, CutoffOfAPointIsTheDiscHolding75PercentOfTheSpectrum) {
  // A single lit pixel has a flat spectrum: 75% of the square lies within sqrt(0.75 / pi).
  auto transfer = transferFunction(disc(64, 0));
  ASSERT_TRUE(transfer);
  EXPECT_NEAR(cutoffFrequency(*transfer), std::sqrt(0.75 / 3.14159265), 0.01);
  // Wider blur, lower cutoff, roughly in inverse proportion.
  auto narrow = transferFunction(disc(64, 3)), wide = transferFunction(disc(64, 6));
  ASSERT_TRUE(narrow && wide);
  const double ratio = cutoffFrequency(*narrow) / cutoffFrequency(*wide);
  EXPECT_GT(ratio, 1.6);
  EXPECT_LT(ratio, 2.5);
}

TEST(Analysis, BlackPhotographIsRefused) { EXPECT_FALSE(transferFunction(Image(8, 8, 1))); }

TEST(Analysis, SignalToNoiseAgainstTheStandard) {
  Image standard(10, 10, 1), frame(10, 10, 1);
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x) {
      standard.at(x, y, 0) = 2;
      frame.at(x, y, 0) = 2 + ((x + y) % 2 ? 0.1f : -0.1f);
    }
  auto snr = signalToNoise(frame, standard);
  ASSERT_TRUE(snr);
  EXPECT_NEAR(snr->noise, 0.1, 1e-6);
  EXPECT_NEAR(snr->snr, 20, 1e-4);
  auto mean = averageImages({&standard, &frame});
  ASSERT_TRUE(mean);
  EXPECT_NEAR(mean->at(1, 0, 0), 2.05, 1e-6);
}

TEST(Analysis, LineFit) {
  auto exact = fitLine({1, 2, 3, 4}, {3, 5, 7, 9});
  ASSERT_TRUE(exact);
  EXPECT_NEAR(exact->slope, 2, 1e-12);
  EXPECT_NEAR(exact->intercept, 1, 1e-12);
  EXPECT_NEAR(exact->r2, 1, 1e-12);
  auto scattered = fitLine({1, 2, 3, 4}, {1, 3, 2, 4});
  ASSERT_TRUE(scattered);
  EXPECT_LT(scattered->r2, 0.9);
  EXPECT_FALSE(fitLine({1, 1}, {2, 3}));
}

TEST(Analysis, GradientEnergyPrefersTheSharperImage) {
  EXPECT_GT(gradientEnergy(disc(32, 4)), 0);
  Image flat(8, 8, 1);
  EXPECT_EQ(gradientEnergy(flat), 0);
}

}  // namespace
}  // namespace lfcam
