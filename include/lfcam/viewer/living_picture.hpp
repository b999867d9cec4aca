// The "living picture" of `lfcam export-html`: one self-contained HTML file that refocuses where
// it is clicked with no server. It holds a focal stack (JPEG, base64 data: URLs) through the full
// aperture and one through a small aperture, the index of the sharpest slice of every pixel (from
// the all-in-focus labelling, all_in_focus.hpp: the focus measure regularised across pixels), the
// all-in-focus photograph, and a viewpoint sweep
// (pinhole views around a circle on the lens, observe() of synthetic_camera.hpp). It opens on the
// slice most pixels of the image's central half find sharpest: the subject, as photographs are
// framed. The page is src/viewer/assets/living.html, embedded in the binary; the data replaces its
// placeholder.
//
// A focus range (focus_spread.hpp) is precomputed for a two-ended slider: `rangeEnds` slices of
// the stack (the first, the last, and evenly between) are the ends it stops at, and every pair of
// distinct ends is one photograph, refocusSpread on the depth map (depth.hpp) estimated over the
// stack's slopes; equal ends show that slice.
#pragma once

#include <filesystem>
#include <string>

#include "lfcam/core/light_field.hpp"
#include "lfcam/core/progress.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/focused/focused_calibration.hpp"
#include "lfcam/raw_io/raw_io.hpp"

namespace lfcam {

constexpr int kMaxRangeEnds = 12;  // 66 focus-range photographs

struct LivingPictureOptions {
  int maxSlices = 24;    // focal stack depth (the all-in-focus step grows to fit)
  int sweepFrames = 24;  // viewpoints around the lens
  int jpegQuality = 85;
  bool smallAperture = true;  // a second focal stack through a small aperture (a page control)
  int rangeEnds = 5;          // stops of the focus range slider: rangeEnds (rangeEnds - 1) / 2 photographs; 0: none
  std::string title = "lfcam living picture";
};

// The page's HTML. Usage error for an empty light field or options out of range.
// Cost: about 3 maxSlices + 64 refocus times (all-in-focus with its focus measure, then the
// stacks), plus about 70 for the depth map and a few per focus range (rangeEnds 0 saves them),
// plus the JPEG encoding.
Result<std::string> makeLivingPicture(const LightField& lightField, const LivingPictureOptions& options = {},
                                      const ProgressCallback& progress = {});

// The page written to `output` atomically (`lfcam export-html`, the page step of `lfcam batch`).
Status writeLivingPicture(const std::filesystem::path& output, const LightField& lightField,
                          const LivingPictureOptions& options = {}, const ProgressCallback& progress = {});

// Lytro's living pictures, back: the page over a processed container's own refocus stack
// (raw_io.hpp, readLytroRefocusStack), its JPEG slices as stored. A click focuses where the
// container's depth map says, blending the two slices whose lambdas lie around it; it opens on
// the slice the depth map puts most of the image's central half at. Without a depth map, the
// slider alone, from the middle slice. No viewpoints or all-in-focus: the containers hold none as JPEGs. Usage
// error for fewer than 2 or more than 255 slices.
Result<std::string> makeLytroLivingPicture(const LytroRefocusStack& stack, const std::string& title);
Status writeLytroLivingPicture(const std::filesystem::path& output, const LytroRefocusStack& stack,
                               const std::string& title);

// A focused plenoptic capture's page (focused_render.hpp), on the frame of pixelsPerLens: its virtual
// depth map estimated (focused_depth.hpp), maxSlices photographs refocused at virtual depths evenly
// spaced in 1 / v over the map's confident range (2nd to 98th percentile), so that a click focuses
// at the map's depth there; the total focus; sweepFrames viewpoints on a circle at half the usable
// radius, each all in focus. No small aperture or focus range (LivingPictureOptions' are ignored).
Result<std::string> makeFocusedLivingPicture(const Image& image, const FocusedCalibration& calibration,
                                             double pixelsPerLens, const LivingPictureOptions& options = {},
                                             const ProgressCallback& progress = {});
Status writeFocusedLivingPicture(const std::filesystem::path& output, const Image& image,
                                 const FocusedCalibration& calibration, double pixelsPerLens,
                                 const LivingPictureOptions& options = {}, const ProgressCallback& progress = {});

}  // namespace lfcam
