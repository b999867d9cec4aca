// The synthetic camera (Equation 5), the moving observer (Equation 7), focal stacks and refocus
// at a pixel: fast kernels against the float64 reference on random light fields, the geometry
// against paper-notes.md computed in millimetres, and the properties of synthetic_camera.hpp.
#include "lfcam/render/synthetic_camera.hpp"
#include "render/references.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "random_light_field.hpp"

#include "lfcam/render/focal_stack.hpp"
#include "lfcam/render/refocus.hpp"
#include "lfcam/synth/layered_planes.hpp"
#include "sharpness.hpp"

namespace lfcam {
namespace {

using test::randomLightField;
using test::worstRelativeError;

Image render(const LightField& lightField, const SyntheticCamera& camera, const RenderOptions& options = {}) {
  auto photo = renderSyntheticPhoto(lightField, camera, options);
  EXPECT_TRUE(photo) << photo.error().message;
  return photo ? std::move(*photo) : Image();
}

Image reference(const LightField& lightField, const SyntheticCamera& camera, int supersampling = 1) {
  auto photo = renderSyntheticPhotoReference(lightField, camera, supersampling);
  EXPECT_TRUE(photo) << photo.error().message;
  return photo ? std::move(*photo) : Image();
}

std::vector<Aperture> someApertures(std::mt19937& random) {
  std::uniform_real_distribution<double> offset(-1.5, 1.5), size(0.0, 2.5);
  Image mask(7, 5, 1);
  std::uniform_real_distribution<float> level(0.0f, 1.0f);
  for (float& p : mask.pixels()) p = level(random);
  mask.at(3, 2, 0) = 1;  // the centre view always lets light through
  return {Aperture::full(), Aperture::circle(size(random), offset(random), offset(random)),
          Aperture::square(size(random) + 0.5, offset(random), offset(random)), Aperture::circle(0),
          Aperture::fromMask(std::move(mask))};
}

TEST(SyntheticCamera, FastMatchesReferenceOnRandomLightFields) {
  std::mt19937 random(2005);
  std::uniform_int_distribution<int> views(1, 5), pixels(1, 29);
  std::uniform_real_distribution<double> anySlope(-3.0, 3.0);
  int cases = 0;
  for (int trial = 0; trial < 16; ++trial) {
    const LightFieldShape shape{.nu = views(random),
                                .nv = views(random),
                                .ns = pixels(random),
                                .nt = pixels(random),
                                .channels = trial % 2 ? 3 : 1};
    const bool weighted = trial % 4 >= 2;
    const LightField lightField = randomLightField(shape, random, weighted);
    for (const Aperture& aperture : someApertures(random)) {
      for (double slope : {0.0, anySlope(random), 2.0}) {
        SyntheticCamera camera{.slope = slope, .aperture = aperture};
        auto fast = renderSyntheticPhoto(lightField, camera);
        if (!fast) {  // an aperture beside a small lens may select no view: both must say so
          EXPECT_EQ(fast.error().code, ErrorCode::Usage);
          EXPECT_FALSE(renderSyntheticPhotoReference(lightField, camera));
          continue;
        }
        EXPECT_LT(worstRelativeError(*fast, reference(lightField, camera)), 1e-5)
            << "views " << shape.nu << "x" << shape.nv << " pixels " << shape.ns << "x" << shape.nt << " slope "
            << slope << " aperture " << int(aperture.shape) << (weighted ? " weighted" : "");
        // Quadrature: supersampled between the views, against the reference with as many samples.
        const RenderOptions quadrature{.method = RenderMethod::Quadrature, .supersampling = 3};
        auto fine = renderSyntheticPhoto(lightField, camera, quadrature);
        if (fine) {
          EXPECT_LT(worstRelativeError(*fine, reference(lightField, camera, 3)), 1e-4);
        }
        ++cases;
      }
    }
  }
  EXPECT_GT(cases, 150);
}

TEST(SyntheticCamera, MovedLensPlaneMatchesReference) {
  std::mt19937 random(18);
  const LightField lightField = randomLightField({.nu = 5, .nv = 4, .ns = 23, .nt = 19, .channels = 3}, random, true);
  for (double beta : {0.6, 1.4})
    for (double slope : {-1.0, 0.7}) {
      const SyntheticCamera camera{.slope = slope, .beta = beta, .parallax = 3.0, .aperture = Aperture::circle(1.5)};
      EXPECT_LT(worstRelativeError(render(lightField, camera), reference(lightField, camera)), 1e-5);
    }
}

TEST(SyntheticCamera, FullApertureIsRefocusAndSlopeZeroIsTheMeanOfTheViews) {
  std::mt19937 random(3);
  const LightField lightField = randomLightField({.nu = 4, .nv = 3, .ns = 31, .nt = 20, .channels = 3}, random, false);
  for (double slope : {0.0, -1.25, 2.5}) {
    const Image fast = render(lightField, {.slope = slope});
    const Image plain = refocus(lightField, slope);
    for (std::size_t i = 0; i < fast.pixels().size(); ++i) ASSERT_EQ(fast.pixels()[i], plain.pixels()[i]);
    // Equation 6 in the reference is refocus.hpp's formula.
    EXPECT_LT(worstRelativeError(reference(lightField, {.slope = slope}), refocusReference(lightField, slope)), 1e-9);
  }
  // alpha = 1 (slope 0): the mean of the views.
  const Image photo = render(lightField, {.slope = 0});
  for (int c = 0; c < 3; ++c)
    for (int t = 0; t < 20; ++t)
      for (int s = 0; s < 31; ++s) {
        double mean = 0;
        for (int v = 0; v < 3; ++v)
          for (int u = 0; u < 4; ++u) mean += lightField.at(u, v, s, t, c);
        ASSERT_NEAR(photo.at(s, t, c), mean / 12, 1e-6);
      }
}

TEST(SyntheticCamera, ApertureOfOneViewIsThatSubApertureImage) {
  std::mt19937 random(9);
  const LightField lightField = randomLightField({.nu = 5, .nv = 5, .ns = 24, .nt = 18, .channels = 2}, random, false);
  for (int v = 0; v < 5; ++v)
    for (int u = 0; u < 5; ++u) {
      const double uc = lightField.uFromCentre(u), vc = lightField.vFromCentre(v);
      const Image view = lightField.subApertureImage(u, v);
      for (const Aperture& aperture : {Aperture::circle(0, uc, vc), Aperture::square(0.4, uc, vc)}) {
        const Image photo = render(lightField, {.slope = 0, .aperture = aperture});
        for (std::size_t i = 0; i < view.pixels().size(); ++i) ASSERT_EQ(photo.pixels()[i], view.pixels()[i]);
      }
      // At slope 1 the view is shifted by (-u, -v): compare where the shifted view covers.
      const Image shifted = render(lightField, {.slope = 1, .aperture = Aperture::circle(0, uc, vc)});
      for (int t = 0; t < 18; ++t)
        for (int s = 0; s < 24; ++s) {
          const int ss = s - int(uc), ts = t - int(vc);
          if (ss < 0 || ts < 0 || ss >= 24 || ts >= 18) continue;
          ASSERT_FLOAT_EQ(shifted.at(s, t, 1), view.at(ss, ts, 1));
        }
    }
}

TEST(SyntheticCamera, FlatFieldStaysFlatForEveryApertureAndMethod) {
  LightField lightField({.nu = 7, .nv = 5, .ns = 33, .nt = 26, .channels = 1});
  std::fill(lightField.samples().begin(), lightField.samples().end(), 0.37f);
  std::mt19937 random(4);
  for (const Aperture& aperture : someApertures(random))
    for (RenderMethod method : {RenderMethod::Fast, RenderMethod::Quadrature})
      for (double slope : {-5.5, 0.3, 2.0, 8.0}) {
        auto photo = renderSyntheticPhoto(lightField, {.slope = slope, .aperture = aperture}, {.method = method});
        if (!photo) continue;  // an aperture outside the lens
        // With the centre view (odd counts) in the aperture every pixel sees light; otherwise
        // shifted views can leave pixels no ray reaches (0), but none may be darkened.
        const bool centreInside = aperture.weight(0, 0, 7, 5) > 0;
        for (float p : photo->pixels()) {
          if (p == 0 && !centreInside) continue;
          ASSERT_NEAR(p, 0.37f, 1e-5) << "slope " << slope << " aperture " << int(aperture.shape);
        }
      }
  // A moved lens plane vignettes, but what it shows is still flat.
  for (double beta : {0.5, 2.0}) {
    const Image photo = render(lightField, {.slope = 0.4, .beta = beta, .parallax = 2.0});
    for (float p : photo.pixels()) {
      if (p != 0) {
        ASSERT_NEAR(p, 0.37f, 1e-5);
      }
    }
  }
}

// The ray map against paper-notes.md's geometry, computed in millimetres with F = 1 and the sign
// convention of light_field.hpp (the lens axis flipped against the paper's): a light field whose
// samples are their own u and s indices returns, through a pinhole aperture, the indices of the
// ray each pixel takes.
TEST(SyntheticCamera, RaysFollowTheGeometryOfEquationFive) {
  const int n = 7, size = 40;
  LightField lightField({.nu = n, .nv = n, .ns = size, .nt = size, .channels = 2});
  for (int v = 0; v < n; ++v)
    for (int u = 0; u < n; ++u)
      for (int t = 0; t < size; ++t)
        for (int s = 0; s < size; ++s) lightField.at(u, v, s, t, 0) = float(u), lightField.at(u, v, s, t, 1) = float(s);
  const double du = 2.0, ds = 0.5, r = du / ds;  // mm per view step, mm per pixel
  for (double slope : {-1.5, 0.0, 0.8})
    for (double beta : {0.7, 1.0, 1.25})
      for (int pinhole : {1, 3, 4}) {
        const double uPrime = lightField.uFromCentre(pinhole);
        const SyntheticCamera camera{
            .slope = slope, .beta = beta, .parallax = r, .aperture = Aperture::circle(0, uPrime, 0)};
        const Image photo = reference(lightField, camera);
        const Image fast = render(lightField, camera);
        const double alpha = r / (r - slope);
        int checked = 0;
        for (int x = 0; x < size; ++x) {
          const double sigma = x + 0.5 - size / 2.0;
          // paper-notes.md, in mm: the synthetic film point and lens point.
          const double filmPoint = alpha * sigma * ds, lensPoint = -uPrime * du;
          const double separation = alpha + beta - 1;
          const double uPaper = filmPoint + (lensPoint - filmPoint) * alpha / separation;
          const double sPaper = lensPoint + (filmPoint - lensPoint) * beta / separation;
          const double uIndex = -uPaper / du + (n - 1) / 2.0, sIndex = sPaper / ds + size / 2.0 - 0.5;
          if (uIndex < 0 || uIndex > n - 1 || sIndex < 0 || sIndex > size - 1) continue;
          ASSERT_NEAR(photo.at(x, size / 2, 0), uIndex, 1e-4) << slope << " " << beta << " x " << x;
          ASSERT_NEAR(photo.at(x, size / 2, 1), sIndex, 1e-4) << slope << " " << beta << " x " << x;
          ASSERT_NEAR(fast.at(x, size / 2, 1), sIndex, 1e-3);
          ++checked;
        }
        EXPECT_GT(checked, 5);
      }
}

TEST(SyntheticCamera, BetaNearOneTendsToEquationSix) {
  std::mt19937 random(6);
  const LightField lightField = randomLightField({.nu = 3, .nv = 3, .ns = 20, .nt = 20, .channels = 1}, random, false);
  const Image exact = refocusReference(lightField, 0.75);
  const Image near = reference(lightField, {.slope = 0.75, .beta = 1 + 1e-9, .parallax = 2.5});
  EXPECT_LT(worstRelativeError(near, exact), 1e-5);
}

TEST(SyntheticCamera, RefusesWhatItCannotRender) {
  LightField lightField({.nu = 3, .nv = 3, .ns = 8, .nt = 8, .channels = 1});
  EXPECT_EQ(renderSyntheticPhoto(lightField, {.slope = 0, .beta = 1.5}).error().code, ErrorCode::Usage);
  EXPECT_EQ(renderSyntheticPhoto(lightField, {.aperture = Aperture::circle(0.5, 9, 9)}).error().code, ErrorCode::Usage);
  EXPECT_FALSE(
      renderSyntheticPhoto(lightField, {.slope = -1, .beta = 0.5, .parallax = 1}));  // alpha 0.5 + beta 0.5 = 1
  EXPECT_FALSE(renderSyntheticPhoto(LightField(), {}));
}

// A real stopped-down lens: deeper focus and more noise.
TEST(SyntheticCamera, StoppingDownDeepensFocusAndAddsNoise) {
  const LayeredPlanesScene scene = defaultLayeredPlanesScene(7, 96);
  LightField lightField = std::move(renderLayeredPlanes(scene).lightField);
  // Focused on the background (slope -1): the nearest card (slope 1.6, lower left) is blurred
  // with the full aperture and much less with a small one.
  const int x0 = 26, y0 = 64, x1 = 54, y1 = 84;
  const Image wide = render(lightField, {.slope = -1.0});
  const Image narrow = render(lightField, {.slope = -1.0, .aperture = Aperture::circle(1)});
  EXPECT_GT(test::laplacianVariance(narrow, x0, y0, x1, y1), 2 * test::laplacianVariance(wide, x0, y0, x1, y1));

  // Noise: independent noise in every sample averages down with the number of views.
  LightField flat({.nu = 7, .nv = 7, .ns = 64, .nt = 64, .channels = 1});
  std::mt19937 random(1);
  std::normal_distribution<float> noise(0.5f, 0.1f);
  for (float& p : flat.samples()) p = noise(random);
  auto deviation = [](const Image& image) {
    double sum = 0, squares = 0;
    for (float p : image.pixels()) sum += p, squares += double(p) * p;
    const double n = double(image.pixels().size());
    return std::sqrt(squares / n - (sum / n) * (sum / n));
  };
  const double full = deviation(render(flat, {.slope = 0}));
  const double small = deviation(render(flat, {.slope = 0, .aperture = Aperture::circle(1)}));  // 5 views
  EXPECT_NEAR(full, 0.1 / 7, 0.003);
  EXPECT_NEAR(small, 0.1 / std::sqrt(5.0), 0.005);
}

TEST(Observer, AtAViewWithBetaOneIsThatView) {
  std::mt19937 random(12);
  const LightField lightField = randomLightField({.nu = 5, .nv = 4, .ns = 21, .nt = 17, .channels = 3}, random, false);
  for (int v = 0; v < 4; ++v)
    for (int u = 0; u < 5; ++u) {
      const Observer observer{.u = lightField.uFromCentre(u), .v = lightField.vFromCentre(v)};
      const Image view = lightField.subApertureImage(u, v);
      auto fast = observe(lightField, observer);
      auto slow = observeReference(lightField, observer);
      ASSERT_TRUE(fast && slow);
      for (std::size_t i = 0; i < view.pixels().size(); ++i) {
        ASSERT_EQ(fast->pixels()[i], view.pixels()[i]);
        ASSERT_EQ(slow->pixels()[i], view.pixels()[i]);
      }
    }
}

TEST(Observer, BetweenViewsInterpolatesAndMovedAlongTheAxisMatchesReference) {
  std::mt19937 random(13);
  const LightField lightField = randomLightField({.nu = 4, .nv = 4, .ns = 25, .nt = 20, .channels = 1}, random, true);
  for (const Observer& observer :
       {Observer{.u = 0.3, .v = -0.9}, Observer{.u = 1, .v = 0.5, .beta = 0.8, .parallax = 2},
        Observer{.u = -1, .beta = 1.6, .parallax = 2, .clampToLens = true},
        Observer{.u = -3, .v = 0.4, .clampToLens = true}, Observer{.u = 1.7, .v = 2.2}}) {
    auto fast = observe(lightField, observer);
    auto slow = observeReference(lightField, observer);
    ASSERT_TRUE(fast && slow);
    EXPECT_LT(worstRelativeError(*fast, *slow), 1e-5);
  }
}

TEST(Observer, OutsideTheLensIsVignettedOrClampedToTheClosestRay) {
  std::mt19937 random(14);
  const LightField lightField = randomLightField({.nu = 3, .nv = 3, .ns = 12, .nt = 10, .channels = 1}, random, false);
  auto dark = observe(lightField, {.u = 5, .v = 0});
  ASSERT_TRUE(dark);
  for (float p : dark->pixels()) EXPECT_EQ(p, 0.0f);
  // Clamped: the outermost view in u, the centre row in v.
  auto clamped = observe(lightField, {.u = 5, .v = 0, .clampToLens = true});
  ASSERT_TRUE(clamped);
  const Image edge = lightField.subApertureImage(2, 1);
  for (std::size_t i = 0; i < edge.pixels().size(); ++i) EXPECT_EQ(clamped->pixels()[i], edge.pixels()[i]);
}

TEST(FocalStack, SlicesAreRefocusedPhotosInOrder) {
  std::mt19937 random(15);
  const LightField lightField = randomLightField({.nu = 3, .nv = 3, .ns = 16, .nt = 12, .channels = 1}, random, false);
  const std::vector<double> slopes = evenlySpaced(-1, 1, 5);
  ASSERT_EQ(slopes.size(), 5u);
  EXPECT_DOUBLE_EQ(slopes[2], 0.0);
  int seen = 0;
  ASSERT_TRUE(renderFocalStack(lightField, slopes, {}, {}, [&](int index, double slope, Image&& photo) -> Status {
    EXPECT_EQ(index, seen++);
    const Image expected = refocus(lightField, slope);
    for (std::size_t i = 0; i < photo.pixels().size(); ++i) EXPECT_EQ(photo.pixels()[i], expected.pixels()[i]);
    return {};
  }));
  EXPECT_EQ(seen, 5);
}

TEST(FocalStack, SlopeAtPixelFindsTheDisparityThere) {
  const LayeredPlanesScene scene = defaultLayeredPlanesScene(5, 96);
  const LayeredPlanesLightField layered = renderLayeredPlanes(scene);
  // Centres of the background, the checkerboard card, the ellipse and the nearest card.
  for (auto [x, y] : {std::pair{85, 10}, std::pair{30, 40}, std::pair{70, 60}, std::pair{38, 74}}) {
    auto slope = slopeAtPixel(layered.lightField, x, y, {.minSlope = -2, .maxSlope = 2.5});
    ASSERT_TRUE(slope) << slope.error().message;
    EXPECT_NEAR(*slope, layered.disparity.at(x, y, 0), 0.1) << x << "," << y;
  }
  EXPECT_FALSE(slopeAtPixel(layered.lightField, -1, 3));
}

TEST(FocalStack, FocusDistanceConversionsRoundTrip) {
  const Optics optics = defaultLayeredPlanesScene().optics;
  auto distance = focusDistanceMmFromAlpha(optics, 1.0);
  ASSERT_TRUE(distance);
  EXPECT_NEAR(*distance, 900.0, 1e-9);  // f = 90, F = 100: 1/90 - 1/100 = 1/900
  for (double alpha : {0.95, 1.0, 1.2}) {
    auto d = focusDistanceMmFromAlpha(optics, alpha);
    ASSERT_TRUE(d);
    auto back = alphaFromFocusDistanceMm(optics, *d);
    ASSERT_TRUE(back);
    EXPECT_NEAR(*back, alpha, 1e-12);
  }
  EXPECT_FALSE(focusDistanceMmFromAlpha(optics, 0.8));  // image plane inside f: beyond infinity
  EXPECT_FALSE(focusDistanceMmFromAlpha(Optics{.lensStepMm = 1, .spatialStepMm = 1, .lensToMicrolensMm = 1}, 1));
}

}  // namespace
}  // namespace lfcam
