// lfcam convert INPUT -o OUTPUT: between every light-field format; the output's name chooses its
// format (.lf.h5, an image name for a lenslet image, anything else a folder).
#include <memory>

#include "commands.hpp"
#include "image_output.hpp"
#include "progress_bar.hpp"

namespace lfcam::cli {

void addConvertCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    std::string output;
    std::optional<std::string> layout;
    std::string extension = "png", depth;
    bool sixteenBit = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("convert", "convert a light field to another format");
  addInputOptions(*command, options->input);
  command
      ->add_option("-o,--output", options->output,
                   "output: NAME.lf.h5, a folder, or a lenslet image (.png, .tif, .exr)")
      ->required();
  command
      ->add_option("--layout", options->layout,
                   "write a view folder in this layout (default: chosen by the output name, HCI for folders)")
      ->check(CLI::IsMember({"hci", "rowcol"}));
  command->add_option("--format", options->extension, "image format of a folder's views")
      ->check(CLI::IsMember({"png", "tif", "exr"}));
  CLI::Option* depth = addBitDepthOption(*command, options->depth);
  command->add_flag("--16bit", options->sixteenBit, "the same as --bit-depth 16")->excludes(depth);
  command->callback([options, &job] {
    job = [options]() -> Status {
      LFCAM_ASSIGN_OR_RETURN(auto lightField, loadInput(options->input));
      if (options->sixteenBit) options->depth = "16";
      LightFieldWriteOptions writeOptions{.sampleType = sampleTypeOfDepth(options->depth),
                                          .viewExtension = "." + options->extension};
      if (options->layout)
        writeOptions.format =
            *options->layout == "rowcol" ? LightFieldFormat::RowColumnFolder : LightFieldFormat::HciFolder;
      ProgressBar bar("writing " + options->output);
      return writeLightField(options->output, lightField, writeOptions, [&](double f) { bar(f); });
    };
  });
}

}  // namespace lfcam::cli
