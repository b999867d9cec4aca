// lfcam batch INPUT... -o OUTDIR --steps STEP[,STEP...] [--white W] [--jobs N] [--report FILE] [--spec FILE]:
// one pipeline applied to every capture, several captures at once, resuming where a previous run
// stopped (batch_capture.hpp), going on past a bad capture and listing the failures at the end and
// in the report (OUTDIR/batch-report.json by default).
#include <algorithm>
#include <condition_variable>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

#include <nlohmann/json.hpp>

#include "batch_capture.hpp"
#include "batch_plan.hpp"
#include "commands.hpp"
#include "lfcam/atomic_file.hpp"
#include "progress_bar.hpp"

namespace lfcam::cli {
namespace fs = std::filesystem;

namespace {

// Captures run side by side share oneTBB's one pool (each capture's parallelFor adds tasks to it),
// so the cores are not oversubscribed; more jobs only overlap the serial parts (reading, encoding,
// writing) and cost one light field of memory each, hence half the cores, at most 4.
int defaultJobs() { return std::clamp(int(std::thread::hardware_concurrency()) / 2, 1, 4); }

const char* statusName(BatchOutcome::Status status) {
  switch (status) {
    case BatchOutcome::Status::Done: return "done";
    case BatchOutcome::Status::Skipped: return "skipped";
    case BatchOutcome::Status::Failed: return "failed";
  }
  return "";
}

// Runs every capture on `jobs` threads; the calling thread keeps the progress bar.
std::vector<BatchOutcome> runCaptures(const std::vector<BatchCapture>& captures, const std::vector<BatchStep>& steps,
                                      const InputOptions& input, const fs::path& outputFolder, int jobs) {
  std::vector<BatchOutcome> outcomes(captures.size());
  std::mutex mutex;
  std::condition_variable finishedOne;
  std::size_t next = 0, finished = 0;
  const auto work = [&] {
    const ProgressBar::QuietOnThisThread quiet;
    for (;;) {
      std::size_t index = 0;
      {
        const std::lock_guard lock(mutex);
        if (next == captures.size()) return;
        index = next++;
      }
      BatchOutcome outcome = runBatchCapture(captures[index], steps, input, outputFolder);
      const std::lock_guard lock(mutex);
      outcomes[index] = std::move(outcome);
      ++finished;
      finishedOne.notify_one();
    }
  };
  std::vector<std::thread> workers;
  for (int k = 0; k < std::min<int>(jobs, int(captures.size())); ++k) workers.emplace_back(work);
  {
    ProgressBar bar("batch of " + std::to_string(captures.size()));
    std::unique_lock lock(mutex);
    while (finished < captures.size()) {
      finishedOne.wait(lock);
      bar(double(finished) / double(captures.size()));
    }
  }
  for (std::thread& worker : workers) worker.join();
  return outcomes;
}

Status writeReport(const fs::path& file, const fs::path& outputFolder, const std::vector<BatchStep>& steps,
                   const std::vector<BatchCapture>& captures, const std::vector<BatchOutcome>& outcomes) {
  nlohmann::json report{{"output", outputFolder.string()}, {"steps", nlohmann::json::array()}};
  for (const BatchStep& step : steps) report["steps"].push_back(step.text);
  std::map<std::string, int> counts{{"done", 0}, {"skipped", 0}, {"failed", 0}};
  nlohmann::json entries = nlohmann::json::array();
  for (std::size_t k = 0; k < captures.size(); ++k) {
    const BatchOutcome& outcome = outcomes[k];
    ++counts[statusName(outcome.status)];
    entries.push_back({{"input", captures[k].input.string()},
                       {"name", captures[k].name},
                       {"status", statusName(outcome.status)},
                       {"outputs", outcome.outputs},
                       {"seconds", outcome.seconds},
                       {"error", outcome.error.empty() ? nlohmann::json() : nlohmann::json(outcome.error)}});
  }
  report["captures"] = entries;
  for (const auto& [status, count] : counts) report[status] = count;
  return writeFileAtomically(file, [&](const fs::path& temporary) -> Status {
    std::ofstream out(temporary);
    out << report.dump(2) << "\n";
    if (!out) return makeError(ErrorCode::Io, file.string() + ": cannot write the report");
    return {};
  });
}

}  // namespace

void addBatchCommand(CLI::App& app, Job& job) {
  struct Options {
    std::vector<std::string> inputs, steps;
    std::string output, white, report, spec;
    int jobs = 0;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("batch", "apply steps to many captures in parallel, resuming a previous run");
  command->add_option("INPUT", options->inputs,
                      "light-field files or folders, raws (with --white), folders of them, or globs (quoted)");
  command->add_option("-o,--output", options->output, "output folder: OUTDIR/<input's name>/ per capture");
  command
      ->add_option("--steps", options->steps,
                   "comma-separated: refocus:SLOPE (refocus_SLOPE.png), stack:FROM:TO:N (stack/slice_NNN.png, "
                   "stack/stack.json), edof (all-in-focus.png), depth (depth.pfm, depth.png), page (page.html, the "
                   "living picture of export-html)")
      ->delimiter(',');
  command->add_option("--white", options->white, "the inputs are raw lenslet images of this white image");
  command->add_option("--jobs", options->jobs, "captures at once (default: half the cores, 1 to 4)")
      ->check(CLI::Range(1, 256));
  command->add_option("--report", options->report, "JSON report (default: OUTDIR/batch-report.json)");
  command->add_option("--spec", options->spec,
                      "JSON object standing for the flags: inputs, steps, output, white, jobs, report (flags win)");
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
      const std::vector<std::string>& inputTexts = options->inputs.empty() ? spec.inputs : options->inputs;
      const std::vector<std::string>& stepTexts = options->steps.empty() ? spec.steps : options->steps;
      const fs::path outputFolder = flagOr("--output", options->output, spec.output);
      InputOptions input;
      input.white = flagOr("--white", options->white, spec.white);
      const int jobs = options->jobs > 0 ? options->jobs : spec.jobs.value_or(defaultJobs());
      if (outputFolder.empty()) return makeError(ErrorCode::Usage, "batch: give the output folder with -o");
      if (inputTexts.empty()) return makeError(ErrorCode::Usage, "batch: give at least one INPUT");
      LFCAM_ASSIGN_OR_RETURN(auto steps, parseBatchSteps(stepTexts));
      if (!input.white.empty() && !fs::is_regular_file(input.white))
        return makeError(ErrorCode::Usage, input.white + ": --white: no such file");
      std::vector<fs::path> excluded{outputFolder};
      if (!input.white.empty()) excluded.emplace_back(input.white);
      LFCAM_ASSIGN_OR_RETURN(auto captures, expandBatchInputs(inputTexts, excluded));
      const std::string reportFlag = flagOr("--report", options->report, spec.report);
      const fs::path report = reportFlag.empty() ? outputFolder / "batch-report.json" : fs::path(reportFlag);

      std::error_code ec;
      fs::create_directories(outputFolder, ec);
      if (ec) return makeError(ErrorCode::Io, outputFolder.string() + ": cannot create the folder: " + ec.message());
      const auto outcomes = runCaptures(captures, steps, input, outputFolder, jobs);
      LFCAM_TRY(writeReport(report, outputFolder, steps, captures, outcomes));

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
                  report.c_str());
      if (failed > 0)
        return makeError(ErrorCode::Io, "batch: " + std::to_string(failed) + " of " + std::to_string(captures.size()) +
                                            " captures failed (listed above and in " + report.string() + ")");
      return {};
    };
  });
}

}  // namespace lfcam::cli
