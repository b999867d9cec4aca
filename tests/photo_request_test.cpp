// The photograph request (photo_request.hpp): every combination of focus, aperture, lens plane and
// sampling renders, whichever kernel renderPhoto picks, as the float64 general path does on random
// light fields; the requests the table of refusals lists are refused with their line by the library
// and by the viewer (the command line and Python read the same table: tests/cli, tests/python).
#include "lfcam/photo/photo_request.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <string>

#include <nlohmann/json.hpp>

#include "lfcam/render/focus_spread.hpp"
#include "lfcam/render/refocus.hpp"
#include "lfcam/render/tilted_focus.hpp"
#include "lfcam/render/upsampled_refocus.hpp"
#include "lfcam/viewer/viewer.hpp"
#include "random_light_field.hpp"

namespace lfcam {
namespace {

using test::worstRelativeError;

// A request from name -> text pairs, as the front ends make it.
PhotoRequest requestOf(const std::map<std::string, std::string>& fields) {
  PhotoRequest request;
  for (const auto& [name, text] : fields) {
    const Status set = setPhotoField(request, name, text);
    EXPECT_TRUE(set.ok()) << name << "=" << text << ": " << set.error().message;
  }
  return request;
}

Image randomImage(int width, int height, int channels, std::mt19937& random, float low, float high) {
  Image image(width, height, channels);
  std::uniform_real_distribution<float> value(low, high);
  for (float& pixel : image.pixels()) pixel = value(random);
  return image;
}

// Each combination the equation defines, rendered by renderPhoto (the kernel it picks) and by the
// float64 general path, on random light fields of random sizes, weighted or not, grey or colour.
TEST(PhotoRequest, EveryCombinationMatchesTheFloat64GeneralPath) {
  std::mt19937 random(20261205);
  const std::vector<std::map<std::string, std::string>> combinations = {
      {{"slope", "0.7"}},
      {{"slope", "-1.3"}, {"aperture", "1.2"}, {"aperture-centre", "0.5,-0.25"}},
      {{"focus-plane", "0,0:3,0:0,3"}},                                                      // its plane replaced below
      {{"slope", "0.4"}, {"tilt", "1.5"}, {"tilt-direction", "30"}, {"aperture", "1.5"}},    // tilt x aperture
      {{"slope", "0.4"}, {"tilt", "-2"}, {"aperture", "1"}, {"aperture-shape", "square"}},   // tilt x square
      {{"slope", "0.4"}, {"tilt", "1"}, {"method", "quadrature"}, {"supersampling", "2"}},   // tilt x quadrature
      {{"slope", "0.2"}, {"tilt", "1"}, {"aperture", "0"}, {"aperture-centre", "0.4,0.3"}},  // observer x tilt
      {{"slope", "0.2"}, {"tilt", "1"}, {"aperture", "0"}, {"aperture-centre", "3,-2"}, {"clamp", ""}},  // clamped
      {{"slope", "0.6"}, {"upsample", "2"}},                                                             // the splat
      {{"slope", "0.6"}, {"tilt", "1"}, {"upsample", "2"}},                   // upsample x tilt
      {{"slope", "0.6"}, {"f-number", "2"}, {"upsample", "3"}},               // x aperture
      {{"slope", "0.3"}, {"aperture", "0"}, {"aperture-centre", "0.5,0.5"}},  // observer
      {{"slope", "0.9"}, {"method", "quadrature"}, {"aperture", "1.5"}},
      {{"focus-range", "1:-0.5"}},                                                     // range
      {{"focus-range", "1:-0.5"}, {"aperture", "1.5"}, {"aperture-centre", "0.5,0"}},  // x aperture
      {{"focus-range", "0.8:0"}, {"method", "quadrature"}, {"supersampling", "2"}},    // x quadrature
      {{"focus-range", "0.8:0"}, {"upsample", "2"}},                                   // x upsample
      {{"focus-range", "0.8:0"}, {"aperture", "0"}, {"aperture-centre", "-0.5,1"}},    // x observer
  };
  for (int trial = 0; trial < 12; ++trial) {
    LightField lightField = test::randomTrialLightField(random, trial, 5, 23);
    // At least 2 x 2 views and 4 x 4 pixels, so that an observer and a plane have room.
    if (lightField.nu() < 2 || lightField.nv() < 2 || lightField.ns() < 4 || lightField.nt() < 4)
      lightField = test::randomLightField({.nu = 3, .nv = 4, .ns = 17, .nt = 13, .channels = trial % 2 ? 3 : 1}, random,
                                          trial % 4 >= 2);
    const auto depth = std::make_shared<const Image>(randomImage(lightField.ns(), lightField.nt(), 1, random, -1, 1.5));
    for (std::map<std::string, std::string> fields : combinations) {
      PhotoRequest request = requestOf(fields);
      if (request.focusRange) request.depth = depth;
      auto photo = resolvePhoto(request, lightField);
      ASSERT_TRUE(photo.ok()) << photo.error().message;
      if (fields.count("focus-plane")) {
        // A plane given directly (a search on random data would find any slope): steep enough to cross views.
        photo->film.plane.slope = 0.3;
        photo->film.plane.gradientX = 0.15;
        photo->film.plane.gradientY = -0.1;
      }
      auto fast = renderPhoto(lightField, *photo);
      auto reference = renderPhotoReference(lightField, *photo);
      ASSERT_TRUE(fast.ok() && reference.ok());
      ASSERT_EQ(fast->width(), lightField.ns() * request.upsample);
      ASSERT_EQ(fast->height(), lightField.nt() * request.upsample);
      std::string described;
      for (const auto& [name, text] : fields) described += " " + name + "=" + text;
      EXPECT_LT(worstRelativeError(*fast, *reference), 2e-5)
          << described << "; views " << lightField.nu() << "x" << lightField.nv() << ", pixels " << lightField.ns()
          << "x" << lightField.nt() << (lightField.hasWeight() ? ", weighted" : "");
    }
  }
}

// The general path is Equation 5 itself: on the plain cases it agrees with the kernels that have
// their own oracles (refocus, tilted focus, focus spread).
TEST(PhotoRequest, TheGeneralPathIsTheKernelsOfThePlainCases) {
  std::mt19937 random(7);
  const LightField lightField =
      test::randomLightField({.nu = 5, .nv = 4, .ns = 29, .nt = 23, .channels = 3}, random, true);
  auto general = [&](const PhotoRequest& request) {
    auto photo = resolvePhoto(request, lightField);
    EXPECT_TRUE(photo.ok());
    return *renderPhotoReference(lightField, *photo);
  };
  EXPECT_LT(worstRelativeError(refocus(lightField, 0.8), general(PhotoRequest{.slope = 0.8})), 1e-5);
  const FocusPlane plane = focusPlaneFromTilt(lightField, 0.5, 2.0, 60.0);
  EXPECT_LT(worstRelativeError(refocusTilted(lightField, plane),
                               general(PhotoRequest{.slope = 0.5, .tilt = 2.0, .tiltDirection = 60.0})),
            1e-5);
  const auto depth = std::make_shared<const Image>(randomImage(29, 23, 1, random, -1, 1));
  const Image spread = *refocusSpread(lightField, *depth, -0.5, 0.5);
  EXPECT_LT(worstRelativeError(spread, general(PhotoRequest{.focusRange = FocusRange{0.5, -0.5}, .depth = depth})),
            1e-5);
}

// A photograph through part of the lens is sharper than through the whole of it, away from focus:
// an aperture does what it should on a tilted and a ranged film too.
TEST(PhotoRequest, AStoppedDownTiltIsTheWholeLensOnesAverageOverFewerViews) {
  std::mt19937 random(11);
  const LightField lightField =
      test::randomLightField({.nu = 5, .nv = 5, .ns = 32, .nt = 32, .channels = 1}, random, false);
  const Image whole = *renderPhoto(lightField, PhotoRequest{.slope = 1.0, .tilt = 1.0});
  const Image centre = *renderPhoto(lightField, PhotoRequest{.slope = 1.0, .tilt = 1.0, .aperture = 0.0});
  // A pinhole at the centre is the centre view, whatever the film.
  const Image view = *renderPhoto(lightField, PhotoRequest{.slope = 0.0, .aperture = 0.0});
  EXPECT_LT(worstRelativeError(centre, view), 1e-6);
  // Averaging 25 random views lowers the contrast; one view keeps it.
  auto variance = [](const Image& image) {
    double sum = 0, squares = 0;
    for (float p : image.pixels()) sum += p, squares += double(p) * p;
    const double n = double(image.pixels().size());
    return squares / n - (sum / n) * (sum / n);
  };
  EXPECT_LT(variance(whole), 0.5 * variance(centre));
}

TEST(PhotoRequest, FieldsHaveUniqueNamesAndKnownGroups) {
  std::set<std::string> names;
  for (const PhotoField& field : photoFields()) {
    EXPECT_TRUE(names.insert(field.name).second) << field.name;
    EXPECT_TRUE(std::set<std::string>({"focus", "aperture", "lens", "sampling"}).count(field.group)) << field.name;
    EXPECT_EQ(findPhotoField(field.name), &field);
  }
  EXPECT_EQ(findPhotoField("focus_plane"), findPhotoField("focus-plane"));
  EXPECT_EQ(findPhotoField("aperture-center"), findPhotoField("aperture-centre"));
  EXPECT_EQ(findPhotoField("no-such-field"), nullptr);
  PhotoRequest request;
  EXPECT_FALSE(setPhotoField(request, "no-such-field", "1").ok());
}

TEST(PhotoRequest, MasksOfTheLenssProportionsOnlyAndDepthMapsOfTheViewsSize) {
  std::mt19937 random(3);
  const LightField lightField =
      test::randomLightField({.nu = 5, .nv = 5, .ns = 20, .nt = 16, .channels = 1}, random, false);
  PhotoRequest request{.slope = 0.5};
  request.apertureMask = std::make_shared<const Image>(randomImage(64, 32, 1, random, 0, 1));
  auto refused = resolvePhoto(request, lightField);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().message,
            "aperture-mask: the mask is 64x32 pixels, the lens 5x5 views: it must have the "
            "lens's proportions");
  request.apertureMask = std::make_shared<const Image>(randomImage(33, 32, 1, random, 0, 1));
  EXPECT_TRUE(resolvePhoto(request, lightField).ok());
  PhotoRequest ranged{.focusRange = FocusRange{1, 0}};
  ranged.depth = std::make_shared<const Image>(randomImage(16, 20, 1, random, 0, 1));
  auto wrongSize = resolvePhoto(ranged, lightField);
  ASSERT_FALSE(wrongSize.ok());
  EXPECT_EQ(wrongSize.error().code, ErrorCode::Usage);
  EXPECT_NE(wrongSize.error().message.find("depth: focus spread: the disparity map is 16x20x1, the views 20x16"),
            std::string::npos)
      << wrongSize.error().message;
}

// The table of refusals, through the library and the viewer.
TEST(PhotoRequest, TheTableOfRefusalsIsRefusedByTheLibraryAndTheViewer) {
  std::ifstream in(LFCAM_PHOTO_REFUSALS);
  ASSERT_TRUE(in) << LFCAM_PHOTO_REFUSALS;
  const nlohmann::json table = nlohmann::json::parse(in);
  std::mt19937 random(1);
  ViewerSession session(test::randomLightField({.nu = 5, .nv = 5, .ns = 40, .nt = 40, .channels = 1}, random, false));
  const LightField& lightField = session.lightField();
  for (const auto& entry : table.at("cases")) {
    const std::string message = entry.at("message");
    PhotoRequest request;
    Status status;
    ViewerRequest query{"GET", "/api/image", {}};
    for (const auto& [name, text] : entry.at("fields").items()) {
      if (status) status = setPhotoField(request, name, text.get<std::string>());
      query.params.emplace(name, text.get<std::string>());
    }
    if (status) status = resolvePhoto(request, lightField).ok() ? Status() : resolvePhoto(request, lightField).error();
    ASSERT_FALSE(status.ok()) << message;
    EXPECT_EQ(status.error().code, ErrorCode::Usage) << message;
    EXPECT_NE(status.error().message.find(message), std::string::npos) << status.error().message;
    if (entry.contains("viewer")) continue;
    const ViewerAnswer answer = answerRequest(session, query);
    EXPECT_EQ(answer.status, 400) << message;
    EXPECT_NE(answer.body.find(message), std::string::npos) << answer.body;
    EXPECT_EQ(std::count(answer.body.begin(), answer.body.end(), '\n'), 1) << answer.body;
  }
}

}  // namespace
}  // namespace lfcam
