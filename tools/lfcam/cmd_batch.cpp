// lfcam batch INPUT... -o OUTDIR --steps STEP[,STEP...] [--white W | --whites DB [--any-camera]] [--jobs N]
//             [--dask ADDRESS]
// [--report FILE] [--spec FILE]: one pipeline applied to every capture, several captures at once,
// resuming where a previous run stopped (batch_capture.hpp), going on past a bad capture and listing
// the failures at the end and in the report (OUTDIR/batch-report.json by default). The work is the
// library's (batch_run.hpp); with --dask it is handed to the Python package (dask_handover.cpp).
#include <cstdio>
#include <memory>

#include "commands.hpp"
#include "dask_handover.hpp"
#include "lfcam/batch/batch_run.hpp"
#include "progress_bar.hpp"
#include "raw_input.hpp"

namespace lfcam::cli {
namespace fs = std::filesystem;

void addBatchCommand(CLI::App& app, Job& job) {
  struct Options {
    std::vector<std::string> inputs, steps;
    std::string output, white, whites, report, spec, dask;
    bool anyCamera = false;
    int jobs = 0;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("batch", "apply steps to many captures in parallel, resuming a previous run");
  command->add_option(
      "INPUT", options->inputs,
      "light-field files or folders, raws (with --white or --whites), folders of them, or globs (quoted)");
  command->add_option("-o,--output", options->output, "output folder: OUTDIR/<input's name>/ per capture");
  command->add_option("--steps", options->steps,
                      "comma-separated: refocus:SLOPE (refocus_SLOPE.png), stack:FROM:TO:N (stack/slice_NNN.png, "
                      "stack/stack.json), edof (all-in-focus.png), depth (depth.pfm, depth.png), page (page.html, the "
                      "living picture of export-html), photo:NAME?FIELD=TEXT&... (photo_NAME.png: any photograph, "
                      "its fields lfcam refocus's flags without the dashes, e.g. photo:tilt?slope=0.5&tilt=1), "
                      "volume:SETTINGS (volume.tif: a microscope volume, SETTINGS as lfcam volume --optics takes "
                      "them; the PSF computed once into OUTDIR)");
  command->add_option("--white", options->white, "the inputs are raw lenslet images of this white image");
  addWhitesOptions(*command, options->whites, options->anyCamera);
  command->add_option("--jobs", options->jobs, "captures at once on this machine (default: half the cores, 1 to 4)")
      ->check(CLI::Range(1, 256));
  command->add_option("--dask", options->dask,
                      "run one task per capture on the workers of this Dask scheduler (tcp://HOST:8786); every "
                      "worker must see the inputs and OUTDIR under the same paths (docs/batch.md)");
  command->add_option("--report", options->report, "JSON report (default: OUTDIR/batch-report.json)");
  command->add_option(
      "--spec", options->spec,
      "JSON object standing for the flags: inputs, steps, output, white, whites, any_camera, jobs, dask, "
      "report (flags win)");
  command->callback([options, command, &job] {
    job = [options, command]() -> Status {
      BatchSpec spec;
      if (!options->spec.empty()) {
        LFCAM_ASSIGN_OR_RETURN(spec, readBatchSpec(options->spec));
      }
      const auto flagOr = [&](const std::string& flag, const std::string& value,
                              const std::optional<std::string>& fromSpec) {
        return command->count(flag) > 0 || !fromSpec ? value : *fromSpec;
      };
      std::vector<std::string> steps;  // each --steps split at the commas that start a step
      for (const std::string& text : options->steps)
        for (std::string& step : splitBatchSteps(text)) steps.push_back(std::move(step));
      const BatchRequest request{.inputs = options->inputs.empty() ? spec.inputs : options->inputs,
                                 .steps = options->steps.empty() ? spec.steps : steps,
                                 .output = flagOr("--output", options->output, spec.output),
                                 .white = flagOr("--white", options->white, spec.white),
                                 .whites = flagOr("--whites", options->whites, spec.whites),
                                 .report = flagOr("--report", options->report, spec.report),
                                 .anyCamera = options->anyCamera || spec.anyCamera.value_or(false)};
      LFCAM_ASSIGN_OR_RETURN(auto plan, planBatch(request));
      const std::string dask = flagOr("--dask", options->dask, spec.dask);
      if (!dask.empty()) return handOverToDask(request, dask);

      const int jobs = options->jobs > 0 ? options->jobs : spec.jobs.value_or(defaultBatchJobs());
      std::vector<BatchOutcome> outcomes;
      {
        ProgressBar bar("batch of " + std::to_string(plan.captures.size()));
        LFCAM_ASSIGN_OR_RETURN(outcomes, runBatchCaptures(plan, jobs, [&](double f) { bar(f); }));
      }
      LFCAM_TRY(writeBatchReport(plan, outcomes));
      int done = 0, skipped = 0, failed = 0;
      for (const BatchOutcome& outcome : outcomes) {
        done += outcome.status == BatchOutcome::Status::Done;
        skipped += outcome.status == BatchOutcome::Status::Skipped;
        if (outcome.status == BatchOutcome::Status::Failed) {
          ++failed;
          std::fprintf(stderr, "lfcam: batch: failed: %s\n", outcome.error.c_str());
        }
      }
      std::printf("batch: %d done, %d skipped (complete already), %d failed; report %s\n", done, skipped, failed,
                  plan.report.c_str());
      return batchStatus(plan, outcomes);
    };
  });
}

}  // namespace lfcam::cli
