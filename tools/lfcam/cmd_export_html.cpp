// lfcam export-html INPUT -o PAGE.html: a self-contained "living picture" that refocuses where it
// is clicked, with a precomputed focus range slider, with no server (living_picture.hpp); of a processed Lytro
// container (*-stk.lfp, an Illum picture), over its own stored slices and depth map; of a focused
// plenoptic capture, over photographs rendered from its micro-images at its virtual depths.
#include <memory>

#include "raw_io/lytro_container.hpp"

#include "commands.hpp"
#include "focused_input.hpp"
#include "lfcam/viewer/living_picture.hpp"
#include "progress_bar.hpp"

namespace lfcam::cli {

void addExportHtmlCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    FocusedOptions focused;
    LivingPictureOptions page;
    std::string output;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "export-html",
      "write one self-contained HTML page that refocuses where it is clicked, with a focus range slider and a "
      "viewpoint sweep");
  addInputOptions(*command, options->input);
  addFocusedOptions(*command, options->focused);
  command->add_option("-o,--output", options->output, "the page (.html)")->required();
  command->add_option("--slices", options->page.maxSlices, "focal stack depth")->check(CLI::Range(2, 255));
  command->add_option("--frames", options->page.sweepFrames, "viewpoints in the sweep")->check(CLI::Range(1, 360));
  command->add_option("--quality", options->page.jpegQuality, "JPEG quality of the embedded images")
      ->check(CLI::Range(1, 100));
  command
      ->add_option("--range-ends", options->page.rangeEnds,
                   "stops of the focus range slider, slices from the farthest to the nearest: every pair is one "
                   "precomputed photograph with all between in focus (0: no range slider; default 5)")
      ->check(CLI::Range(0, kMaxRangeEnds));
  command->add_option("--title", options->page.title, "the page's title");
  command->callback([options, &job] {
    job = [options]() -> Status {
      if (isFocusedInput(options->input, options->focused)) {
        LFCAM_ASSIGN_OR_RETURN(auto capture, loadFocusedInput(options->input, options->focused));
        ProgressBar bar("making " + options->output);
        return writeFocusedLivingPicture(options->output, capture.image, capture.calibration,
                                         pixelsPerLens(options->focused, capture.calibration), options->page,
                                         [&](double f) { bar(f); });
      }
      // A processed container: its own slices. (A raw frame is decoded like any raw, with --white or --whites.)
      if (!options->input.decodesRaw() && looksLikeLytroContainer(options->input.path)) {
        LFCAM_ASSIGN_OR_RETURN(auto stack, readLytroRefocusStack(options->input.path));
        return writeLytroLivingPicture(options->output, stack, options->page.title);
      }
      LFCAM_ASSIGN_OR_RETURN(auto lightField, loadInput(options->input));
      ProgressBar bar("making " + options->output);
      return writeLivingPicture(options->output, lightField, options->page, [&](double f) { bar(f); });
    };
  });
}

}  // namespace lfcam::cli
