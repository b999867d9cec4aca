// lfcam score DISPARITY GROUND_TRUTH [--mask PLANES] [--border N] [--badpix T]... [--json]: the HCI
// benchmark's scores of any disparity map, lfcam's or another method's (disparity_scores.hpp).
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "lfcam/edof/disparity_scores.hpp"
#include "lfcam/io/image_io.hpp"

namespace lfcam::cli {
namespace {

Result<Image> readDisparity(const std::string& path) {
  LFCAM_ASSIGN_OR_RETURN(auto image, readImage(path));
  if (image.channels() != 1)
    return makeError(ErrorCode::Usage, path + ": " + std::to_string(image.channels()) +
                                           " channels, but a disparity map has one (as the benchmark's .pfm)");
  return image;
}

std::string sizeOf(const Image& image) { return std::to_string(image.width()) + "x" + std::to_string(image.height()); }

}  // namespace

void addScoreCommand(CLI::App& app, Job& job) {
  struct Options {
    std::string estimate, truth, mask;
    int border = 15;
    std::vector<double> thresholds;  // BadPix besides the benchmark's three
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "score", "the HCI benchmark's scores of a disparity map: BadPix 0.01/0.03/0.07, MSE x100, bumpiness");
  command->add_option("disparity", options->estimate, "disparity map to score (pixels per view step, .pfm .exr .tif)")
      ->required();
  command->add_option("truth", options->truth, "its ground truth, same size (e.g. the benchmark's gt_disp_lowres.pfm)")
      ->required();
  command->add_option("--mask", options->mask,
                      "planar surfaces for the bumpiness, nonzero on planes (the benchmark's mask_planes.png); "
                      "default: where the ground truth itself is planar. BadPix and MSE use every pixel");
  command->add_option("--border", options->border, "pixels left out along each edge, as the benchmark")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option(
          "--badpix", options->thresholds,
          "BadPix at this threshold too (pixels per view step; repeatable), e.g. 0.035 to score a map of twice "
          "the benchmark's resolution as strictly, in the scene, as 0.07 at its own")
      ->check(CLI::PositiveNumber);
  command->add_flag(
      "--json", options->json,
      "print a JSON object (badpix_0.01, badpix_0.03, badpix_0.07, one per --badpix, mse_x100, bumpiness, pixels)");
  command->callback([options, &job] {
    job = [options]() -> Status {
      LFCAM_ASSIGN_OR_RETURN(auto estimate, readDisparity(options->estimate));
      LFCAM_ASSIGN_OR_RETURN(auto truth, readDisparity(options->truth));
      if (estimate.width() != truth.width() || estimate.height() != truth.height())
        return makeError(ErrorCode::Usage, options->truth + ": the ground truth is " + sizeOf(truth) + " but " +
                                               options->estimate + " is " + sizeOf(estimate));
      Image planes;
      if (!options->mask.empty()) {
        LFCAM_ASSIGN_OR_RETURN(auto mask, readImage(options->mask));
        if (mask.width() != truth.width() || mask.height() != truth.height())
          return makeError(ErrorCode::Usage,
                           options->mask + ": the mask is " + sizeOf(mask) + " but the ground truth " + sizeOf(truth));
        planes = Image(mask.width(), mask.height(), 1);
        for (int y = 0; y < mask.height(); ++y)
          for (int x = 0; x < mask.width(); ++x) planes.at(x, y, 0) = mask.at(x, y, 0);
      }
      auto scores = scoreHci(estimate, truth, planes, options->border);
      if (!scores) return makeError(scores.error().code, options->truth + ": " + scores.error().message);
      std::vector<std::pair<double, double>> badPix = {
          {0.01, scores->badPix001}, {0.03, scores->badPix003}, {0.07, scores->badPix007}};
      for (double threshold : options->thresholds) {
        LFCAM_ASSIGN_OR_RETURN(auto extra, scoreDisparity(estimate, truth, threshold, options->border));
        badPix.emplace_back(threshold, extra.badPix);
      }
      const std::string planesFrom = options->mask.empty() ? "the ground truth's planes" : options->mask;
      if (options->json) {
        nlohmann::json json = {{"disparity", options->estimate}, {"truth", options->truth},
                               {"mse_x100", scores->mse100},     {"bumpiness", scores->bumpiness},
                               {"planes", planesFrom},           {"border", options->border},
                               {"pixels", scores->pixels}};
        for (const auto& [threshold, share] : badPix) json[badPixKey(threshold)] = share;
        std::printf("%s\n", json.dump(2).c_str());
      } else {
        for (const auto& [threshold, share] : badPix) {
          char name[32];
          std::snprintf(name, sizeof name, "BadPix(%g)", threshold);
          std::printf("%-13s %7.2f %%\n", name, share);
        }
        std::printf(
            "MSE x100      %7.3f\nBumpiness     %7.3f   (on %s)\npixels        %7ld   (%d-pixel border left out)\n",
            scores->mse100, scores->bumpiness, planesFrom.c_str(), scores->pixels, options->border);
      }
      return {};
    };
  });
}

}  // namespace lfcam::cli
