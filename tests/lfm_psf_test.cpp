// The light-field microscope's PSF, stage by stage: the Debye integral against the Airy pattern
// and Parseval, the Fresnel propagation against its direct float64 sum, the whole PSF's geometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <tuple>
#include <vector>

#include "lfcam/lfm/psf.hpp"
#include "lfcam/lfm/sparse_psf.hpp"
#include "lfm/psf_stages.hpp"
#include "lfm_small_microscope.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace lfm_psf_test {

constexpr double kPi = std::numbers::pi;

// Encircled energy of the native image out to v = vMax: Simpson's rule over 2 pi r I(r) dr.
double encircledEnergy(const LfmOptics& optics, double depthUm, double vMax, PupilModel pupil) {
  const double beta = 2 * kPi * optics.imageCutoffPerUm();
  const int intervals = int(vMax / 0.15) / 2 * 2;  // 20 a period of the rings
  const double h = vMax / beta / intervals;
  std::vector<double> radii(intervals + 1);
  for (int i = 0; i <= intervals; ++i) radii[i] = i * h;
  const auto field = debyeField(optics, depthUm, radii, pupil);
  EXPECT_TRUE(field);
  double sum = 0;
  for (int i = 0; i <= intervals; ++i) {
    const double weight = (i == 0 || i == intervals) ? 1 : (i % 2 ? 4 : 2);
    sum += weight * 2 * kPi * radii[i] * std::norm(field->at(i));
  }
  return sum * h / 3;
}

}  // namespace lfm_psf_test

using namespace lfm_psf_test;

TEST(LfmDebye, GaussLegendreIsExactForPolynomials) {
  std::vector<double> x, w;
  for (int n : {1, 2, 5, 64, 301}) {
    lfm::gaussLegendre(n, x, w);
    double sum = 0, even = 0;
    for (int i = 0; i < n; ++i) sum += w[i], even += w[i] * std::pow(x[i], 2 * n - 2);
    EXPECT_NEAR(sum, 2, 1e-13) << n;
    EXPECT_NEAR(even, 2.0 / (2 * n - 1), 1e-13) << n;
  }
}

TEST(LfmDebye, InFocusParaxialIsTheAiryPattern) {
  // I(r) = pi kappa^2 [2 J1(v) / v]^2, v = 2 pi r NA / (lambda M): unit energy, its peak pi kappa^2.
  const LfmOptics optics;
  const double kappa = optics.imageCutoffPerUm(), beta = 2 * kPi * kappa;
  std::vector<double> radii;
  for (double v = 0; v <= 30; v += 0.05) radii.push_back(v / beta);
  const auto field = debyeField(optics, 0, radii, PupilModel::Paraxial);
  ASSERT_TRUE(field);
  const double peak = kPi * kappa * kappa;
  double worst = 0;
  for (std::size_t i = 0; i < radii.size(); ++i) {
    const double v = beta * radii[i];
    const double airy = v == 0 ? 1 : std::pow(2 * std::cyl_bessel_j(1.0, v) / v, 2);
    worst = std::max(worst, std::abs(std::norm(field->at(i)) / peak - airy));
  }
  EXPECT_LT(worst, 1e-12);  // measured 2.2e-15
  RecordProperty("max_deviation_from_airy", std::to_string(worst));
}

TEST(LfmDebye, InFocusAbbeSineIsNearTheAiryPattern) {
  // The aplanatic apodization 1 / sqrt(cos theta) in rho brightens the pupil's rim: the high-NA
  // pattern departs from Airy by a few per cent of its peak at NA 1.2 / 1.35, by far less at low NA.
  for (const auto& [na, tolerance] : {std::pair{1.2, 0.05}, std::pair{0.1, 1e-3}}) {
    LfmOptics optics{.numericalAperture = na};
    const double kappa = optics.imageCutoffPerUm(), beta = 2 * kPi * kappa;
    std::vector<double> radii;
    for (double v = 0; v <= 30; v += 0.05) radii.push_back(v / beta);
    const auto field = debyeField(optics, 0, radii, PupilModel::AbbeSine);
    ASSERT_TRUE(field);
    const double peak = std::norm(field->at(0));
    double worst = 0;
    for (std::size_t i = 0; i < radii.size(); ++i) {
      const double v = beta * radii[i];
      const double airy = v == 0 ? 1 : std::pow(2 * std::cyl_bessel_j(1.0, v) / v, 2);
      worst = std::max(worst, std::abs(std::norm(field->at(i)) / peak - airy));
    }
    EXPECT_LT(worst, tolerance) << "NA " << na;
    std::printf("NA %g: max |I/I0 - Airy| = %.3g\n", na, worst);
  }
}

TEST(LfmDebye, EnergyIsTheSameAtEveryDepth) {
  // Unit energy by construction (Parseval over the pupil); what the quadrature yields out to
  // v = 150, where the rings left out hold about 2 / (pi v) ~ 0.4 % in focus (more with the Abbe
  // sine pupil's brighter rim).
  const LfmOptics optics;
  for (PupilModel pupil : {PupilModel::AbbeSine, PupilModel::Paraxial}) {
    const double inFocus = encircledEnergy(optics, 0, 150, pupil);
    EXPECT_NEAR(inFocus, 1, 1e-2);  // measured 0.99325 (Abbe sine), 0.99576 (paraxial)
    for (double depth : pupil == PupilModel::AbbeSine ? std::vector{-2.0, 1.0} : std::vector{1.0}) {
      const double energy = encircledEnergy(optics, depth, 150, pupil);
      EXPECT_NEAR(energy, inFocus, 1.5e-3) << "depth " << depth;  // measured 8.1e-4 at -2 um
      std::printf("pupil %d depth %g: energy %.6f (in focus %.6f)\n", int(pupil), depth, energy, inFocus);
    }
  }
}

TEST(LfmDebye, NativeFieldOnTheGridIsRadialAndMatchesTheDirectIntegral) {
  const LfmOptics optics;
  const LfmPoint point{0, 0, 1.5};
  const int n = 51;  // one lenslet's window: 17 pixels x 3
  const auto profile =
      lfm::radialProfile(optics, PupilModel::AbbeSine, point.zUm, lfm::maxRadiusOnGrid(optics, point, n));
  const auto fast = lfm::nativeFieldFromProfile(optics, profile, point, n);
  const auto direct = lfm::nativeFieldDirect(optics, PupilModel::AbbeSine, point, n);
  double peak = 0, worst = 0, asymmetry = 0;
  for (const auto& value : direct) peak = std::max(peak, std::abs(value));
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const auto value = direct[y * n + x];
      worst = std::max(worst, std::abs(fast[y * n + x] - value) / peak);
      // Mirrored in x, in y, and about the diagonal: the same radius, the same field.
      for (auto other : {direct[y * n + (n - 1 - x)], direct[(n - 1 - y) * n + x], direct[x * n + y]})
        asymmetry = std::max(asymmetry, std::abs(other - value) / peak);
    }
  EXPECT_LT(asymmetry, 1e-12);
  EXPECT_LT(worst, 1e-3);
  std::printf("profile vs direct: %.3g of the peak; asymmetry %.3g\n", worst, asymmetry);
}

TEST(LfmPsf, FresnelPropagationConservesEnergy) {
  // Parseval: |H| = 1, so the propagation only moves energy.
  const LfmOptics optics;
  const auto model = LfmPsf::create(optics, 3);
  ASSERT_TRUE(model) << model.error().message;
  const int n = model->samplesAcross();
  const auto native = model->nativeField({5, -3, 2});
  std::vector<std::complex<float>> field(native.begin(), native.end());
  lfm::applyMicrolenses(optics, n, field.data());
  double before = 0, after = 0;
  for (auto value : field) before += std::norm(std::complex<double>(value));
  lfm::FresnelTransfer transfer(n, optics.sampleSpacingUm(), optics.sampleHeightUm(), optics.wavelengthUm(),
                                optics.microlensFocalLengthUm);
  transfer.propagate(field.data());
  for (auto value : field) after += std::norm(std::complex<double>(value));
  EXPECT_NEAR(after / before, 1, 1e-5);
  std::printf("energy after / before: 1 %+.3g\n", after / before - 1);
}

TEST(LfmPsf, DirectFresnelSumMatchesTheFft) {
  // On a 60-sample window of 3 x 3 lenslets, an in-focus point on the axis: its light stays
  // under the centre lenslet, so the FFT's periodic window and the direct sum's open plane agree.
  // Square pixels of a square array; a hexagonal array's bricks, shorter than wide.
  LfmOptics hexagonal = test::smallMicroscope();
  hexagonal.array = MicrolensLayout::Hexagonal;
  for (const LfmOptics& optics : {test::smallMicroscope(), frameOptics(hexagonal, 10)}) {
    const auto model = LfmPsf::create(optics, 3, PupilModel::AbbeSine);
    ASSERT_TRUE(model) << model.error().message;
    const int n = model->samplesAcross();
    ASSERT_EQ(n, 60);  // 3 lenslets of 10 pixels, 2 samples each
    const LfmPoint point{0.3, 0, 0};
    std::vector<std::complex<double>> masked = model->nativeField(point);
    lfm::applyMicrolenses(optics, n, masked.data());
    const auto direct = lfm::fresnelDirect(masked, n, optics.sampleSpacingUm(), optics.sampleHeightUm(),
                                           optics.wavelengthUm(), optics.microlensFocalLengthUm);
    const auto fft = model->sensorField(point);
    // Compared under the centre lenslet, where 92 % of the light lands: the rest, spread by the
    // lenslets' edges, leaves the window and comes back in on the FFT's periodic one alone.
    double difference = 0, norm = 0;
    const double dx = optics.sampleSpacingUm(), dy = optics.sampleHeightUm(), half = 0.5 * optics.rowPitchUm();
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        if (std::hypot(lfm::sampleCoordinate(x, n, dx), lfm::sampleCoordinate(y, n, dy)) > half) continue;
        const std::size_t i = std::size_t(y) * n + x;
        difference += std::norm(std::complex<double>(fft[i]) - direct[i]);
        norm += std::norm(direct[i]);
      }
    const double relative = std::sqrt(difference / norm);
    EXPECT_LT(relative, 0.02) << microlensLayoutName(optics.array);
    std::printf("%s: FFT vs direct Fresnel under the centre lenslet: relative L2 %.3g\n",
                microlensLayoutName(optics.array), relative);
  }
}

TEST(LfmPsf, InFocusPointOnTheAxisLightsTheCentreLensletSymmetrically) {
  const LfmOptics optics;
  const auto model = LfmPsf::create(optics, 3);
  ASSERT_TRUE(model) << model.error().message;
  const Image psf = model->psf({0, 0, 0});
  const int n = psf.width();
  ASSERT_EQ(n, 47);
  double total = 0, peak = 0, cx = 0, cy = 0, asymmetry = 0, centre = 0;
  const double half = 0.5 * optics.microlensPitchUm / optics.pixelSizeUm;  // 7.7 pixels
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const double value = psf.at(x, y, 0);
      total += value, cx += value * (x - n / 2), cy += value * (y - n / 2);
      peak = std::max(peak, value);
      if (std::abs(x - n / 2) < half && std::abs(y - n / 2) < half) centre += value;
    }
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      for (float other : {psf.at(n - 1 - x, y, 0), psf.at(x, n - 1 - y, 0), psf.at(y, x, 0)})
        asymmetry = std::max(asymmetry, std::abs(other - psf.at(x, y, 0)) / peak);
  EXPECT_LT(std::abs(cx / total), 1e-3);
  EXPECT_LT(std::abs(cy / total), 1e-3);
  EXPECT_LT(asymmetry, 1e-4);
  EXPECT_GT(centre / total, 0.9);
  EXPECT_GT(total, 0.95);
  EXPECT_LE(total, 1.0 + 1e-4);
  std::printf("total %.4f, centre lenslet %.4f, centroid (%.2g, %.2g) px, asymmetry %.3g\n", total, centre / total,
              cx / total, cy / total, asymmetry);
}

TEST(LfmPsf, PointOneLensletAsideLightsTheNextLenslet) {
  // In focus, a point imaged on the next lenslet's centre (pitch / M in the specimen) moves the
  // pattern by one pitch, 100 / 6.5 pixels: its centroid under that lenslet's cell.
  const LfmOptics optics;
  const auto model = LfmPsf::create(optics, 3);
  ASSERT_TRUE(model);
  const Image psf = model->psf({optics.microlensPitchUm / optics.magnification, 0, 0});
  const int n = psf.width();
  const double pitch = optics.microlensPitchUm / optics.pixelSizeUm;
  double total = 0, cell = 0, cx = 0, cy = 0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const double value = psf.at(x, y, 0);
      total += value;
      if (std::abs(x - n / 2 - pitch) > pitch / 2 || std::abs(y - n / 2) > pitch / 2) continue;
      cell += value, cx += value * (x - n / 2), cy += value * (y - n / 2);
    }
  EXPECT_GT(cell / total, 0.85);
  EXPECT_NEAR(cx / cell, pitch, 0.1);
  EXPECT_NEAR(cy / cell, 0, 1e-3);
  std::printf("next lenslet: %.3f of the light, centroid %.3f px (pitch %.3f)\n", cell / total, cx / cell, pitch);
}

TEST(LfmPsf, RefusesWindowsAndSamplingItCannotModel) {
  auto refusal = [](const LfmOptics& optics, int lenslets) {
    const auto model = LfmPsf::create(optics, lenslets);
    return model ? std::string() : model.error().message;
  };
  EXPECT_EQ(refusal(LfmOptics{}, 4), "lenslets across 4 must be odd, in [1, 201]");
  EXPECT_EQ(refusal(LfmOptics{.numericalAperture = 1.4, .immersionIndex = 1.33}, 3),
            "NA 1.4 above the immersion index 1.33: no light reaches the objective");
  EXPECT_EQ(refusal(LfmOptics{.pixelSizeUm = 10, .supersample = 1}, 3),
            "sample spacing 10 um aliases the field after the microlenses (up to 0.0675 cycles/um): raise "
            "supersample to at least 2");
  LfmOptics hexagonalFrame = frameOptics(LfmOptics{.array = MicrolensLayout::Hexagonal}, 15);
  EXPECT_EQ(hexagonalFrame.supersample, 4);  // raised from 3: 15 x 3 samples a pitch has no half
  hexagonalFrame.supersample = 3;
  EXPECT_EQ(refusal(hexagonalFrame, 3),
            "a hexagonal frame of 15 pixels a lenslet needs an even supersample: its shifted rows sit half a pitch "
            "over");
  EXPECT_EQ(LfmPsf::lensletsFor(LfmOptics{}, 0), 3);
  EXPECT_EQ(LfmPsf::lensletsFor(LfmOptics{}, 2), 9);  // blur radius 60 * 2 * tan(alpha) = 233 um: 3 + 1 a side
}

TEST(LfmPsfSet, HoldsEverySliceAndVoxelOfALenslet) {
  const LfmOptics optics;
  const LfmGrid grid{.pixelsPerLenslet = 15, .voxelsPerLenslet = 3, .depthsUm = {0, 0.5}};
  const auto set = computePsfSet(optics, grid, 3);
  ASSERT_TRUE(set) << set.error().message;
  const int n = set->pixelsAcross;
  ASSERT_EQ(n, 45);
  ASSERT_EQ(set->values.size(), std::size_t(2 * 3 * 3) * n * n);
  EXPECT_NEAR(set->optics.pixelSizeUm, 100.0 / 15, 1e-12);
  // Voxel (2, 0) sits a third of a lenslet right of and above the centre, in the specimen.
  EXPECT_NEAR(set->point(1, 2, 0).xUm, 100.0 / 3 / 60, 1e-12);
  EXPECT_NEAR(set->point(1, 2, 0).yUm, -100.0 / 3 / 60, 1e-12);
  EXPECT_EQ(set->point(1, 2, 0).zUm, 0.5);
  // Every phase, copied by symmetry or computed, is the PSF of its own point within 1e-4 of the
  // peak (the FFT grid of an even sample count is not quite symmetric), and not its neighbour's.
  const auto model = LfmPsf::create(set->optics, 3);
  ASSERT_TRUE(model);
  for (int depth = 0; depth < 2; ++depth)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        const Image direct = model->psf(set->point(depth, i, j));
        const float* stored = set->psf(depth, i, j);
        const float* other = set->psf(depth, (i + 1) % 3, j);
        double peak = 0, worst = 0, change = 0;
        for (int p = 0; p < n * n; ++p) peak = std::max(peak, double(direct.pixels()[p]));
        for (int p = 0; p < n * n; ++p) {
          worst = std::max(worst, std::abs(double(stored[p]) - direct.pixels()[p]) / peak);
          change = std::max(change, std::abs(double(other[p]) - direct.pixels()[p]) / peak);
        }
        EXPECT_LT(worst, 1e-4) << depth << " " << i << " " << j;
        EXPECT_GT(change, 1e-2) << depth << " " << i << " " << j;
      }
}

TEST(LfmPsfSet, RefusesGridsItCannotPlace) {
  auto refusal = [](const LfmGrid& grid) {
    const auto set = computePsfSet(LfmOptics{}, grid, 3);
    return set ? std::string() : set.error().message;
  };
  EXPECT_EQ(refusal({.pixelsPerLenslet = 1, .depthsUm = {0}}), "pixels per lenslet 1 outside [2, 255]");
  EXPECT_EQ(refusal({.pixelsPerLenslet = 15, .voxelsPerLenslet = 16, .depthsUm = {0}}),
            "voxels per lenslet (supersample) 16 must be in [1, 15] (the pixels per lenslet)");
  EXPECT_EQ(refusal({.pixelsPerLenslet = 15}), "no slices: the volume needs at least one");
}

TEST(LfmSparsePsf, KeepsTheBrightestPixelsHoldingTheAskedEnergy) {
  const LfmGrid grid{.pixelsPerLenslet = 15, .voxelsPerLenslet = 1, .depthsUm = {1.5}};
  const auto set = computePsfSet(LfmOptics{}, grid, 5);
  ASSERT_TRUE(set) << set.error().message;
  const int n = set->pixelsAcross;
  double total = 0;
  int nonzero = 0;
  for (int p = 0; p < n * n; ++p) total += set->psf(0, 0, 0)[p], nonzero += set->psf(0, 0, 0)[p] > 0;
  const LfmSparsePsf all = sparsePsf(set.value(), 1);
  EXPECT_EQ(int(all.splats.size()), nonzero);
  EXPECT_EQ(all.reach, 2);
  const LfmSparsePsf most = sparsePsf(set.value(), 0.95);
  double kept = 0;
  float smallest = 1;
  for (const LfmSplat& splat : most.of(0, 0, 0)) kept += splat.weight, smallest = std::min(smallest, splat.weight);
  EXPECT_GE(kept, 0.95 * total - 1e-6);
  EXPECT_LT(kept - smallest, 0.95 * total);  // one splat fewer would not do
  EXPECT_LT(most.splats.size(), all.splats.size() / 2);
  std::printf("1.5 um: %zu of %d pixels hold 95 %% of the energy\n", most.splats.size(), n * n);
  // Each splat is a pixel of the dense PSF, where its lenslet offset and pixel say.
  for (const LfmSplat& splat : all.of(0, 0, 0)) {
    const int x = (splat.dx + 2) * 15 + splat.pixel % 15, y = (splat.dy + 2) * 15 + splat.pixel / 15;
    ASSERT_EQ(splat.weight, set->psf(0, 0, 0)[y * n + x]);
  }
}

TEST(LfmPsfCache, KeepsTheSplatsAndRefusesOtherSettings) {
  test::TempDir dir;
  const LfmOptics optics;
  const LfmGrid grid{.pixelsPerLenslet = 15, .voxelsPerLenslet = 1, .depthsUm = {0.25}};
  const auto psf = computeSparsePsf(optics, grid, 0.99);
  ASSERT_TRUE(psf) << psf.error().message;
  const std::string path = (dir.path() / "psf.h5").string();
  const Status written = writePsfCache(psf.value(), path);
  ASSERT_TRUE(written) << written.error().message;

  const auto read = readPsfCache(path, optics, grid, 0.99);
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->grid.depthsUm, grid.depthsUm);
  EXPECT_EQ(read->reach, psf->reach);
  EXPECT_EQ(read->begins, psf->begins);
  ASSERT_EQ(read->splats.size(), psf->splats.size());
  for (std::size_t k = 0; k < psf->splats.size(); ++k) {
    EXPECT_EQ(read->splats[k].pixel, psf->splats[k].pixel);
    EXPECT_EQ(read->splats[k].dx, psf->splats[k].dx);
    EXPECT_EQ(read->splats[k].dy, psf->splats[k].dy);
    EXPECT_EQ(read->splats[k].weight, psf->splats[k].weight);
  }

  auto refusal = [&](const LfmOptics& other, const LfmGrid& otherGrid, double keep, PupilModel pupil) {
    const auto result = readPsfCache(path, other, otherGrid, keep, pupil);
    return result ? std::string() : result.error().message;
  };
  const std::string again = ": compute the PSFs again for these settings";
  EXPECT_EQ(refusal(LfmOptics{.numericalAperture = 1.1}, grid, 0.99, PupilModel::AbbeSine),
            path + ": made for NA 1.2, not 1.1" + again);
  EXPECT_EQ(refusal(LfmOptics{.supersample = 5}, grid, 0.99, PupilModel::AbbeSine),
            path + ": made for field samples per pixel 3, not 5" + again);
  EXPECT_EQ(refusal(optics, grid, 0.99, PupilModel::Paraxial),
            path + ": made for pupil (0 Abbe sine, 1 paraxial) 0, not 1" + again);
  EXPECT_EQ(
      refusal(optics, {.pixelsPerLenslet = 15, .voxelsPerLenslet = 3, .depthsUm = {0.25}}, 0.99, PupilModel::AbbeSine),
      path + ": made for voxels per lenslet 1, not 3" + again);
  EXPECT_EQ(
      refusal(optics, {.pixelsPerLenslet = 15, .voxelsPerLenslet = 1, .depthsUm = {0.5}}, 0.99, PupilModel::AbbeSine),
      path + ": made for a slice at 0.25 um, not 0.5" + again);
  EXPECT_EQ(refusal(optics, grid, 0.95, PupilModel::AbbeSine),
            path + ": made for kept PSF energy 0.99, not 0.95" + again);

  const Status unwritable = writePsfCache(psf.value(), (dir.path() / "missing" / "psf.h5").string());
  ASSERT_FALSE(unwritable);
  EXPECT_EQ(unwritable.error().message, (dir.path() / "missing" / "psf.h5").string() + ": cannot write: the folder " +
                                            (dir.path() / "missing").string() + " does not exist");
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "missing"));

  test::writeBytes(dir.path() / "other.h5", "not HDF5");
  const auto other = readPsfCache((dir.path() / "other.h5").string(), optics, grid, 0.99);
  ASSERT_FALSE(other);
  EXPECT_EQ(other.error().code, ErrorCode::Io);
}

namespace lfm_psf_test {

LfmOptics hexagonalMicroscope() {
  LfmOptics optics = test::smallMicroscope();
  optics.array = MicrolensLayout::Hexagonal;
  return optics;
}

// |U|^2 at (x, y) micrometres from the window's centre, bilinear between the samples.
double intensityAt(const std::vector<std::complex<float>>& field, int n, double dx, double dy, double x, double y) {
  const double fx = x / dx + 0.5 * (n - 1), fy = y / dy + 0.5 * (n - 1);
  const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
  const double tx = fx - x0, ty = fy - y0;
  auto at = [&](int i, int j) { return double(std::norm(field[std::size_t(j) * n + i])); };
  return (1 - ty) * ((1 - tx) * at(x0, y0) + tx * at(x0 + 1, y0)) +
         ty * ((1 - tx) * at(x0, y0 + 1) + tx * at(x0 + 1, y0 + 1));
}

}  // namespace lfm_psf_test

TEST(LfmPsf, HexagonalArrayPlacesItsLensletsAndApertures) {
  const LfmOptics optics = hexagonalMicroscope();
  const double p = optics.microlensPitchUm, h = optics.rowPitchUm();
  EXPECT_NEAR(h, 40 * std::sqrt(3.0) / 2, 1e-12);
  // Odd rows, above and below the axis, half a pitch toward +x.
  for (const auto& [x, y, cx, cy] : {std::tuple{3.0, 2.0, 0.0, 0.0}, std::tuple{19.0, 30.0, 20.0, h},
                                     std::tuple{-18.0, -33.0, -20.0, -h}, std::tuple{41.0, 2 * h - 1, 40.0, 2 * h},
                                     std::tuple{0.0, 0.6 * h, 0.0, 0.0}, std::tuple{p / 2 - 1, 0.6 * h, p / 2, h}}) {
    const lfm::LensletCentre centre = lfm::nearestLenslet(optics, x, y);
    EXPECT_NEAR(centre.xUm, cx, 1e-9) << x << " " << y;
    EXPECT_NEAR(centre.yUm, cy, 1e-9) << x << " " << y;
  }
  // The apertures pass the fill factor of the plane: the hexagons shrunk by its square root.
  for (double fill : {1.0, 0.6}) {
    LfmOptics shrunk = optics;
    shrunk.microlensFillFactor = fill;
    shrunk.supersample = 8;
    const int n = 400;
    std::vector<std::complex<double>> field(std::size_t(n) * n, 1.0);
    lfm::applyMicrolenses(shrunk, n, field.data());
    double open = 0;
    for (auto value : field) open += std::abs(value) > 0.5;
    EXPECT_NEAR(open / field.size(), fill, 0.01) << fill;
  }
}

TEST(LfmPsf, HexagonalArrayPsfHasSixFoldSymmetry) {
  // A point on the axis, in focus and 6 um off: the array is symmetric under turns of 60 degrees
  // about the centre lenslet, so the sensor's light is too (between samples by interpolation);
  // not under 90 degrees, which tells the test can see a square array's symmetry from a
  // hexagon's. The six neighbours' cells receive equal light. Finely sampled: the interpolation
  // between samples is most of the difference.
  LfmOptics optics = hexagonalMicroscope();
  optics.supersample = 6;
  for (double z : {0.0, 6.0}) {
    const auto model = LfmPsf::create(optics, LfmPsf::lensletsFor(optics, z));
    ASSERT_TRUE(model) << model.error().message;
    const int n = model->samplesAcross();
    const double dx = optics.sampleSpacingUm(), dy = optics.sampleHeightUm();
    const auto field = model->sensorField({0, 0, z});
    const double radius = z == 0 ? 0.45 * optics.microlensPitchUm : 1.4 * optics.microlensPitchUm;
    auto turned = [&](double degrees) {
      const double c = std::cos(degrees * kPi / 180), s = std::sin(degrees * kPi / 180);
      double difference = 0, total = 0;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const double x = lfm::sampleCoordinate(i, n, dx), y = lfm::sampleCoordinate(j, n, dy);
          if (std::hypot(x, y) > radius) continue;
          const double here = intensityAt(field, n, dx, dy, x, y);
          difference += std::abs(here - intensityAt(field, n, dx, dy, c * x - s * y, s * x + c * y));
          total += here;
        }
      return difference / total;
    };
    const double sixty = turned(60), ninety = turned(90);
    EXPECT_LT(sixty, 0.01) << z;
    EXPECT_GT(ninety, 5 * sixty) << z;
    std::vector<double> neighbours(6, 0.0);
    double all = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double x = lfm::sampleCoordinate(i, n, dx), y = lfm::sampleCoordinate(j, n, dy);
        const double energy = std::norm(field[std::size_t(j) * n + i]);
        all += energy;
        const lfm::LensletCentre centre = lfm::nearestLenslet(optics, x, y);
        const double distance = std::hypot(centre.xUm, centre.yUm);
        if (std::abs(distance - optics.microlensPitchUm) > 1e-6) continue;
        const int sector = int(std::lround(std::atan2(centre.yUm, centre.xUm) / (kPi / 3)) + 6) % 6;
        neighbours[sector] += energy;
      }
    const auto [low, high] = std::minmax_element(neighbours.begin(), neighbours.end());
    EXPECT_LT((*high - *low) / *high, 0.005) << z;
    std::printf("z %g um: |I - I turned 60| %.3g, 90 %.3g of the light; neighbours' cells %.4f-%.4f of it\n", z, sixty,
                ninety, *low / all, *high / all);
  }
}

TEST(LfmPsf, HexagonalFrameKeepsEachDepthsEnergyInItsBricks) {
  // A rectified hexagonal frame's pixels tile the window brick by brick (every other row half a
  // pitch over): they hold every sample's energy once, which is the native image's unit energy
  // less what leaves the window.
  const LfmOptics optics = frameOptics(hexagonalMicroscope(), 10);
  EXPECT_EQ(lfm::hexagonalBrickPixels(optics), 10);
  for (double z : {-6.0, 0.0, 4.0}) {
    const auto model = LfmPsf::create(optics, LfmPsf::lensletsFor(optics, z));
    ASSERT_TRUE(model) << model.error().message;
    const LfmPoint point{0.4, -0.3, z};
    const auto field = model->sensorField(point);
    double samples = 0;
    for (auto value : field) samples += std::norm(std::complex<double>(value));
    samples *= optics.sampleSpacingUm() * optics.sampleHeightUm();
    const Image psf = model->psf(point);
    double pixels = 0;
    for (float value : psf.pixels()) pixels += value;
    EXPECT_NEAR(pixels / samples, 1, 1e-5) << z;
    EXPECT_GT(pixels, 0.97) << z;
    EXPECT_LT(pixels, 1 + 1e-4) << z;
    std::printf("z %g um: the bricks hold %.5f, the samples %.5f\n", z, pixels, samples);
  }
}

TEST(LfmPsf, HexagonalFrameMovesThePsfABrickWithTheLattice) {
  // Moving the point by the lattice vector (pitch / 2, row pitch) moves its light by one row of
  // bricks, and by one brick along x from a shifted row to an unshifted one: the array and the
  // frame's bricks are the same after the move.
  const LfmOptics optics = frameOptics(hexagonalMicroscope(), 10);
  const int lenslets = LfmPsf::lensletsFor(optics, 3) + 2;
  const auto model = LfmPsf::create(optics, lenslets);
  ASSERT_TRUE(model) << model.error().message;
  const double m = optics.magnification;
  const LfmPoint point{0.3, -0.2, 3}, moved{0.3 + 0.5 * optics.microlensPitchUm / m, -0.2 + optics.rowPitchUm() / m, 3};
  const Image a = model->psf(point), b = model->psf(moved);
  const int n = 10, centre = lenslets / 2;
  double difference = 0, total = 0, peak = 0;
  for (int by = 1; by + 2 < lenslets; ++by)
    for (int bx = 1; bx + 2 < lenslets; ++bx) {
      const bool shiftedRow = (by - centre) % 2 != 0;
      for (int v = 0; v < n; ++v)
        for (int u = 0; u < n; ++u) {
          const double before = a.at(bx * n + u, by * n + v, 0);
          const double after = b.at((bx + (shiftedRow ? 1 : 0)) * n + u, (by + 1) * n + v, 0);
          difference = std::max(difference, std::abs(after - before));
          total += before;
          peak = std::max(peak, before);
        }
    }
  EXPECT_GT(total, 0.9);
  EXPECT_LT(difference / peak, 1e-3);
  std::printf("moved by the lattice: %.3g of the peak apart over %.3f of the light\n", difference / peak, total);
}

}  // namespace lfcam
