// The fine search's SIMD row kernel (src/edof/fine_cost_row.hpp) against its scalar reference, bit
// for bit, on every instruction set this CPU runs (Highway's dispatch forced to each in turn): random
// planes; disparities that take samples past every border, whole and half shifts among them; stars
// of odd and even apertures, a single row and column, one and three channels; with and without the
// interpolation-bias and noise terms; widths below one vector and with tails.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <hwy/targets.h>

#include "edof/fine_cost_row.hpp"

namespace lfcam::edof {
namespace {

// Planes of random values for the star through the centre view of nu x nv views, grouped into
// subsets as depth.cpp groups them (each side of the centre along u and along v, the centre row,
// the centre column), the empty subsets left out.
struct RandomStar {
  std::vector<std::vector<float>> planes;
  std::vector<float> xx, yy, xy;
  FineCostViews views;

  RandomStar(int nu, int nv, int channels, int ns, int nt, std::mt19937& random) {
    std::uniform_real_distribution<float> value(0, 1);
    const auto randomPlane = [&] {
      std::vector<float> plane(std::size_t(ns) * nt);
      for (float& v : plane) v = value(random);
      return plane;
    };
    views = {.ns = ns, .nt = nt, .channels = channels};
    const int referenceU = (nu - 1) / 2, referenceV = (nv - 1) / 2;
    std::vector<unsigned> halves;
    const auto add = [&](int u, int v) {
      for (int c = 0; c < channels; ++c) planes.push_back(randomPlane());
      views.uc.push_back(u - 0.5 * (nu - 1));
      views.vc.push_back(v - 0.5 * (nv - 1));
      const int du = u - referenceU, dv = v - referenceV;
      halves.push_back((du < 0) | (du > 0) << 1 | (dv < 0) << 2 | (dv > 0) << 3 | (dv == 0) << 4 | (du == 0) << 5);
    };
    add(referenceU, referenceV);
    for (int v = 0; v < nv; ++v)
      for (int u = 0; u < nu; ++u) {
        const int du = u - referenceU, dv = v - referenceV;
        if ((du != 0 || dv != 0) && (du == 0 || dv == 0 || std::abs(du) == std::abs(dv))) add(u, v);
      }
    halves[0] = 0;
    views.subsets.assign(halves.size(), 0);
    for (int h = 0; h < kMaxCostSubsets; ++h) {
      int count = 0;
      for (std::size_t i = 1; i < halves.size(); ++i)
        if ((halves[i] >> h) & 1) {
          views.subsets[i] |= 1u << views.viewsIn.size();
          ++count;
        }
      if (count > 0) views.viewsIn.push_back(count);
    }
    for (const std::vector<float>& plane : planes) views.planes.push_back(plane.data());
    xx = randomPlane(), yy = randomPlane(), xy = randomPlane();
    views.xx = xx.data(), views.yy = yy.data(), views.xy = xy.data();
  }
};

TEST(FineCostRow, EverySimdTargetMatchesTheScalarReferenceBitForBit) {
  std::mt19937 random(4181);
  std::uniform_real_distribution<double> nearDisparity(-3, 3), farDisparity(-40, 40);
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  struct Layout {
    int nu, nv, channels;
  };
  for (std::int64_t target : targets) {
    hwy::SetSupportedTargetsForTest(target);
    for (const Layout& layout : {Layout{9, 9, 1}, Layout{5, 5, 3}, Layout{4, 6, 1}, Layout{7, 1, 1}, Layout{1, 4, 2}})
      for (int ns : {1, 3, 7, 8, 17, 37}) {
        const int nt = 3 + ns % 5;
        RandomStar star(layout.nu, layout.nv, layout.channels, ns, nt, random);
        const std::size_t subsets = star.views.viewsIn.size();
        for (double locking : {0.0, 0.8})
          for (const ViewNoise& noise : {ViewNoise{}, ViewNoise{0.01, 0}, ViewNoise{0.003, 0.4}}) {
            star.views.locking = locking;
            star.views.noise = noise;
            for (int y = 0; y < nt; ++y) {
              // Every fourth pixel far past the plane's borders, every fifth on a whole or half shift.
              std::vector<float> disparity(ns);
              for (int x = 0; x < ns; ++x)
                disparity[x] = float(x % 4 == 3   ? farDisparity(random)
                                     : x % 5 == 4 ? std::round(2 * nearDisparity(random)) / 2
                                                  : nearDisparity(random));
              const double offset = (y % 3 - 1) * 0.125 + (y == 1 ? nearDisparity(random) : 0.0);
              std::vector<std::vector<float>> fast(subsets), reference(subsets);
              std::vector<float*> fastRows, referenceRows;
              for (std::size_t j = 0; j < subsets; ++j) {
                fast[j].assign(ns, std::numeric_limits<float>::quiet_NaN());
                reference[j].assign(ns, 0.0f);
                fastRows.push_back(fast[j].data()), referenceRows.push_back(reference[j].data());
              }
              fineCostRow(star.views, y, disparity.data(), offset, fastRows.data());
              fineCostRowReference(star.views, y, disparity.data(), offset, referenceRows.data());
              for (std::size_t j = 0; j < subsets; ++j)
                for (int x = 0; x < ns; ++x)
                  ASSERT_EQ(std::bit_cast<std::uint32_t>(fast[j][x]), std::bit_cast<std::uint32_t>(reference[j][x]))
                      << hwy::TargetName(target) << ", " << layout.nu << " x " << layout.nv << " views, "
                      << layout.channels << " channels, " << ns << " x " << nt << ", locking " << locking << ", noise "
                      << noise.variance << " / " << noise.neighbourCorrelation << ", row " << y << ", subset " << j
                      << ", x " << x << ": " << fast[j][x] << " against " << reference[j][x] << " at disparity "
                      << disparity[x] << " + " << offset;
            }
          }
      }
  }
  hwy::SetSupportedTargetsForTest(0);  // back to the CPU's best
}

}  // namespace
}  // namespace lfcam::edof
