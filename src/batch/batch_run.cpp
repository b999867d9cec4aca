#include "lfcam/batch/batch_run.hpp"

#include <algorithm>
#include <condition_variable>
#include <fstream>
#include <map>
#include <mutex>
#include <thread>

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/parallel.hpp"
#include "lfcam/lfm/volume_request.hpp"

namespace lfcam {
namespace fs = std::filesystem;

// Captures run side by side share oneTBB's one pool (each capture's parallelFor adds tasks to it),
// so the cores are not oversubscribed; more jobs only overlap the serial parts (reading, encoding,
// writing) and cost one light field of memory each, hence half the cores, at most 4.
int defaultBatchJobs() { return std::clamp(int(std::thread::hardware_concurrency()) / 2, 1, 4); }

const char* batchStatusName(BatchOutcome::Status status) {
  switch (status) {
    case BatchOutcome::Status::Done: return "done";
    case BatchOutcome::Status::Skipped: return "skipped";
    case BatchOutcome::Status::Failed: return "failed";
  }
  return "";
}

Status prepareBatch(const BatchPlan& plan, const ProgressCallback& progress) {
  std::error_code ec;
  fs::create_directories(plan.output, ec);
  if (ec) return makeError(ErrorCode::Io, plan.output.string() + ": cannot create the folder: " + ec.message());
  std::vector<const BatchStep*> uncached;
  for (const BatchStep& step : plan.steps)
    if (step.kind == BatchStep::Kind::Volume && !fs::exists(batchPsfPath(step, plan.output))) uncached.push_back(&step);
  if (uncached.empty()) return {};
  // The first capture that reads: an unreadable one fails as itself when its turn comes.
  for (const BatchCapture& capture : plan.captures) {
    Result<LightField> frame = loadCapture(capture.input, plan.white);
    if (!frame) continue;
    for (std::size_t k = 0; k < uncached.size(); ++k) {
      LfmVolumeRequest request = uncached[k]->volume;
      request.psfPath = batchPsfPath(*uncached[k], plan.output).string();
      const Status cached = cacheVolumePsf(*frame, request, capture.input.string(), [&](double f) {
        if (progress) progress((double(k) + f) / double(uncached.size()));
      });
      if (!cached) return makeError(cached.error().code, uncached[k]->text + ": " + cached.error().message);
    }
    return {};
  }
  return {};
}

Result<std::vector<BatchOutcome>> runBatchCaptures(const BatchPlan& plan, int jobs, const ProgressCallback& progress) {
  LFCAM_TRY(prepareBatch(plan));
  const std::vector<BatchCapture>& captures = plan.captures;
  std::vector<BatchOutcome> outcomes(captures.size());
  std::mutex mutex;
  std::condition_variable finishedOne;
  std::size_t next = 0, finished = 0;
  const auto work = [&] {
    for (;;) {
      std::size_t index = 0;
      {
        const std::lock_guard lock(mutex);
        if (next == captures.size()) return;
        index = next++;
      }
      BatchOutcome outcome;
      if (cancellationRequested())
        outcome.error = captures[index].input.string() + ": cancelled";
      else
        outcome = runBatchCapture(captures[index], plan.steps, plan.white, plan.output);
      const std::lock_guard lock(mutex);
      outcomes[index] = std::move(outcome);
      ++finished;
      finishedOne.notify_one();
    }
  };
  std::vector<std::thread> workers;
  for (int k = 0; k < std::min<int>(jobs, int(captures.size())); ++k) workers.emplace_back(work);
  {
    std::unique_lock lock(mutex);
    while (finished < captures.size()) {
      finishedOne.wait(lock);
      if (progress) progress(double(finished) / double(captures.size()));
    }
  }
  for (std::thread& worker : workers) worker.join();
  return outcomes;
}

Result<std::string> writeBatchReport(const BatchPlan& plan, const std::vector<BatchOutcome>& outcomes) {
  nlohmann::json report{{"output", plan.output.string()}, {"steps", nlohmann::json::array()}};
  for (const BatchStep& step : plan.steps) report["steps"].push_back(step.text);
  std::map<std::string, int> counts{{"done", 0}, {"skipped", 0}, {"failed", 0}};
  nlohmann::json entries = nlohmann::json::array();
  for (std::size_t k = 0; k < plan.captures.size(); ++k) {
    const BatchOutcome& outcome = outcomes.at(k);
    ++counts[batchStatusName(outcome.status)];
    entries.push_back({{"input", plan.captures[k].input.string()},
                       {"name", plan.captures[k].name},
                       {"status", batchStatusName(outcome.status)},
                       {"outputs", outcome.outputs},
                       {"seconds", outcome.seconds},
                       {"error", outcome.error.empty() ? nlohmann::json() : nlohmann::json(outcome.error)}});
  }
  report["captures"] = entries;
  for (const auto& [status, count] : counts) report[status] = count;
  const std::string text = report.dump(2) + "\n";
  LFCAM_TRY(writeFileAtomically(plan.report, [&](const fs::path& temporary) -> Status {
    std::ofstream out(temporary);
    out << text;
    if (!out) return makeError(ErrorCode::Io, plan.report.string() + ": cannot write the report");
    return {};
  }));
  return text;
}

Status batchStatus(const BatchPlan& plan, const std::vector<BatchOutcome>& outcomes) {
  const auto failed = std::count_if(outcomes.begin(), outcomes.end(), [](const BatchOutcome& outcome) {
    return outcome.status == BatchOutcome::Status::Failed;
  });
  if (failed == 0) return {};
  return makeError(ErrorCode::Io, "batch: " + std::to_string(failed) + " of " + std::to_string(outcomes.size()) +
                                      " captures failed (listed above and in " + plan.report.string() + ")");
}

}  // namespace lfcam
