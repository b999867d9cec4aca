// lfcam export-html INPUT -o PAGE.html: a self-contained "living picture" that refocuses where it
// is clicked, with no server (living_picture.hpp).
#include <memory>

#include "commands.hpp"
#include "lfcam/atomic_file.hpp"
#include "lfcam/living_picture.hpp"
#include "progress_bar.hpp"

namespace lfcam::cli {

void addExportHtmlCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    LivingPictureOptions page;
    std::string output;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "export-html", "write one self-contained HTML page that refocuses where it is clicked, with a viewpoint sweep");
  addInputOptions(*command, options->input);
  command->add_option("-o,--output", options->output, "the page (.html)")->required();
  command->add_option("--slices", options->page.maxSlices, "focal stack depth")->check(CLI::Range(2, 255));
  command->add_option("--frames", options->page.sweepFrames, "viewpoints in the sweep")->check(CLI::Range(1, 360));
  command->add_option("--quality", options->page.jpegQuality, "JPEG quality of the embedded images")
      ->check(CLI::Range(1, 100));
  command->add_option("--title", options->page.title, "the page's title");
  command->callback([options, &job] {
    job = [options]() -> Status {
      LFCAM_ASSIGN_OR_RETURN(auto lightField, loadInput(options->input));
      auto make = [&] {
        ProgressBar bar("making " + options->output);
        return makeLivingPicture(lightField, options->page, [&](double f) { bar(f); });
      };
      LFCAM_ASSIGN_OR_RETURN(const std::string html, make());
      return writeFileAtomically(options->output, [&](const std::filesystem::path& temporary) -> Status {
        std::FILE* file = std::fopen(temporary.c_str(), "wb");
        if (!file) return makeError(ErrorCode::Io, options->output + ": cannot write");
        const bool written = std::fwrite(html.data(), 1, html.size(), file) == html.size();
        if (std::fclose(file) != 0 || !written) return makeError(ErrorCode::Io, options->output + ": cannot write");
        return {};
      });
    };
  });
}

}  // namespace lfcam::cli
