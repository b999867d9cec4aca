// lfcam views INPUT -o DIR [--format png|tif|exr] [--bit-depth 8|16|float] [--mosaic FILE]: every
// sub-aperture image (view_RR_CC.EXT, 1-based row and column, so the folder reads back as a light
// field) and a contact sheet of them. 8-bit PNGs are sRGB for quick looks; 16-bit and float views
// hold linear radiance (image_output.hpp).
#include <memory>

#include "commands.hpp"
#include "image_output.hpp"
#include "lfcam/render/contact_sheet.hpp"
#include "progress_bar.hpp"

namespace lfcam::cli {

void addViewsCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    std::string output;
    std::string mosaic;
    std::string extension = "png", depth;
    bool sixteenBit = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("views", "write every sub-aperture image, and a contact sheet");
  addInputOptions(*command, options->input);
  command->add_option("-o,--output", options->output, "folder for view_RR_CC.png (or .tif, .exr)")->required();
  command->add_option("--mosaic", options->mosaic, "also write a contact sheet of all views to this image");
  command->add_option("--format", options->extension, "image format of the views")
      ->check(CLI::IsMember({"png", "tif", "exr"}));
  CLI::Option* depth = addBitDepthOption(*command, options->depth);
  command->add_flag("--16bit", options->sixteenBit, "the same as --bit-depth 16")->excludes(depth);
  command->callback([options, &job] {
    job = [options]() -> Status {
      if (options->sixteenBit) options->depth = "16";
      const LightFieldWriteOptions writeOptions{.format = LightFieldFormat::RowColumnFolder,
                                                .sampleType = sampleTypeOfDepth(options->depth),
                                                .viewExtension = "." + options->extension};
      // Refused here, before the input is read, as writeLightField would refuse it after.
      LFCAM_TRY(imageWriteOptionsFor(std::filesystem::path(options->output) / ("view_01_01." + options->extension),
                                     options->depth));
      std::optional<ImageWriteOptions> mosaicOptions;
      if (!options->mosaic.empty()) {
        LFCAM_ASSIGN_OR_RETURN(auto checked, imageWriteOptionsFor(options->mosaic, options->depth));
        mosaicOptions = checked;
      }
      LFCAM_ASSIGN_OR_RETURN(auto lightField, loadInput(options->input));
      {
        ProgressBar bar("writing views");
        LFCAM_TRY(writeLightField(options->output, lightField, writeOptions, [&](double f) { bar(f); }));
      }
      if (mosaicOptions) LFCAM_TRY(writeImage(options->mosaic, contactSheet(lightField), *mosaicOptions));
      return {};
    };
  });
}

}  // namespace lfcam::cli
