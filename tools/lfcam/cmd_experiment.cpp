// lfcam experiment NAME -o DIR [--quick]: one of the paper's measurements, as a report folder.
#include <memory>

#include "commands.hpp"
#include "lfcam/experiments/experiments.hpp"
#include "progress_bar.hpp"

namespace lfcam::cli {

void addExperimentCommand(CLI::App& app, Job& job) {
  struct Options {
    std::string name, output;
    bool quick = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("experiment", "reproduce one of the paper's experiments and write its report");
  std::string names;
  for (const auto& n : experimentNames()) names += (names.empty() ? "" : ", ") + n;
  command->add_option("name", options->name, "the experiment: " + names)->required();
  command->add_option("-o,--output", options->output, "report folder (report.md, report.html, results.json, ...)")
      ->required();
  command->add_flag("--quick", options->quick, "reduced size: seconds instead of minutes (for tests)");
  command->callback([options, &job] {
    job = [options]() -> Status {
      ProgressBar bar("experiment " + options->name);
      return runExperiment(options->name, options->output,
                           ExperimentOptions{.quick = options->quick, .progress = [&bar](double f) { bar(f); }});
    };
  });
}

}  // namespace lfcam::cli
