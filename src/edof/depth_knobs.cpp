// The table of depth settings and the options-file reader (depth_knobs.hpp).
#include "lfcam/edof/depth_knobs.hpp"

#include <array>
#include <fstream>
#include <sstream>

#include "core/json_reader.hpp"

namespace lfcam {

std::span<const DepthKnob> depthKnobs() {
  using O = DepthOptions;
  static const std::array<DepthKnob, 21> knobs{{
      {"range", "min", "smallest disparity searched (default: metadata, else -2)", &O::disparityMin, -1e3, 1e3},
      {"range", "max", "largest disparity searched (default: metadata, else 2)", &O::disparityMax, -1e3, 1e3},
      {"range", "labels", "candidate disparities (0: one per 0.1 px, within [16, 96])", &O::labels, 0, 1024},
      {"cost", "prefilter-sigma",
       "views smoothed by a Gaussian of this sigma (px) before matching (0: none; -1: automatic, 0.55 where the views "
       "are noisy)",
       &O::prefilterSigma, -1, 10},
      {"cost", "offset-radius",
       "views less their brightness offset from the centre view (a sheen), averaged over about this radius (px; 0: "
       "none)",
       &O::offsetRadius, 0, 256},
      {"cost", "offset-epsilon", "regulariser of the offsets' guided filter, squared disparity", &O::offsetEpsilon,
       1e-9, 100},
      {"cost", "offset-passes", "first maps at half resolution that align the views for the offsets", &O::offsetPasses,
       1, 8},
      {"cost", "defocus-weight", "weight of the defocus cue against the correspondence cue", &O::defocusWeight, 0, 100},
      {"aggregation", "filter-radius", "guided filter window of the cost: (2 r + 1)^2 pixels", &O::filterRadius, 0, 64},
      {"aggregation", "filter-epsilon", "guided filter regulariser, squared linear luminance", &O::filterEpsilon, 0, 1},
      {"regularisation", "smoothness", "scale of both jump penalties of the optimisation (0: none)", &O::smoothness, 0,
       100},
      {"regularisation", "contrast-radius",
       "window whose cost contrast, with the image's, scales the penalties at a pixel (0: the image's only)",
       &O::contrastRadius, 0, 64},
      {"refinement", "refine-steps", "fine search: steps per label on each side (0: none)", &O::refineSteps, 0, 16},
      {"refinement", "refine-radius", "guided filter window of the fine search: (2 r + 1)^2 pixels", &O::refineRadius,
       0, 64},
      {"refinement", "refine-smooth-radius",
       "window radius of the quadratic fit to the map the first fine search starts from (0 or 1: none)",
       &O::refineSmoothRadius, 0, 64},
      {"refinement", "refine-rounds",
       "rounds of fine search and cleanup, each from the map the last cleaned, at half its spacing (needs "
       "refine-steps > 0)",
       &O::refineRounds, 1, 8},
      {"cleanup", "fill-lambda", "edge-aware fill strength (needs refine-steps > 0; 0: none)", &O::fillLambda, 0, 1e4},
      {"cleanup", "fill-sigma", "centre-view colour difference that weakens a fill link to 1/e", &O::fillSigma, 1e-6,
       10},
      {"cleanup", "occlusion-band", "pixels beside nearer surfaces given back to the background (0: none)",
       &O::occlusionBand, 0, 64},
      {"cleanup", "median-radius", "weighted median window (0: none)", &O::medianRadius, 0, 64},
      {"cleanup", "median-sigma", "guide difference that weighs a median neighbour 0.6", &O::medianSigma, 1e-6, 10},
  }};
  return knobs;
}

Status readDepthOptions(const std::filesystem::path& file, DepthOptions& options) {
  const std::string where = file.string();
  std::ifstream in(file, std::ios::binary);
  if (!in) return makeError(ErrorCode::Io, where + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::exception&) {
    return makeError(ErrorCode::Format, where + ": not JSON");
  }
  const json_reader::JsonObject object(json, where, "");
  LFCAM_TRY(object.requireObject());
  DepthOptions read = options;
  for (const DepthKnob& knob : depthKnobs()) {
    Status status = std::visit(
        [&](auto member) -> Status {
          auto& value = read.*member;
          using T = std::remove_reference_t<decltype(value)>;
          if constexpr (std::is_same_v<T, int>)
            return object.integer(knob.name, value, static_cast<long long>(knob.min), static_cast<long long>(knob.max));
          else if constexpr (std::is_same_v<T, double>)
            return object.number(knob.name, value, knob.min, knob.max);
          else
            return object.optionalNumber(knob.name, value, knob.min, knob.max);
        },
        knob.member);
    LFCAM_TRY(status);
  }
  LFCAM_TRY(object.noUnknownKeys());
  options = read;
  return {};
}

}  // namespace lfcam
