// analysis: the transfer function against a direct DFT, the 75% cutoff, SNR and line fits.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "analysis/references.hpp"
#include "lfcam/analysis.hpp"

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
