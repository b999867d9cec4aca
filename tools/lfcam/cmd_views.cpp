// lfcam views INPUT -o DIR [--mosaic FILE]: every sub-aperture image (view_RR_CC.png, 1-based row
// and column, so the folder reads back as a light field) and a contact sheet of them.
#include <memory>

#include "commands.hpp"
#include "lfcam/contact_sheet.hpp"
#include "lfcam/image_io.hpp"
#include "progress_bar.hpp"

namespace lfcam::cli {

void addViewsCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    std::string output;
    std::string mosaic;
    bool sixteenBit = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("views", "write every sub-aperture image, and a contact sheet");
  addInputOptions(*command, options->input);
  command->add_option("-o,--output", options->output, "folder for view_RR_CC.png")->required();
  command->add_option("--mosaic", options->mosaic, "also write a contact sheet of all views to this image");
  command->add_flag("--16bit", options->sixteenBit, "16-bit linear PNGs");
  command->callback([options, &job] {
    job = [options]() -> Status {
      auto lightField = loadInput(options->input);
      if (!lightField) return lightField.error();
      {
        ProgressBar bar("writing views");
        LFCAM_TRY(writeLightField(options->output, *lightField,
                                  {.format = LightFieldFormat::RowColumnFolder, .sixteenBit = options->sixteenBit},
                                  [&](double f) { bar(f); }));
      }
      if (!options->mosaic.empty()) LFCAM_TRY(writeImage(options->mosaic, contactSheet(*lightField)));
      return {};
    };
  });
}

}  // namespace lfcam::cli
