// A whole batch on one machine, and its report: `lfcam batch`, lfcam.batch.run in Python, and, for
// the report, the same batch run on a Dask cluster (whose workers call runBatchCapture).
#pragma once

#include <string>
#include <vector>

#include "lfcam/batch_capture.hpp"
#include "lfcam/batch_plan.hpp"
#include "lfcam/progress.hpp"
#include "lfcam/result.hpp"

namespace lfcam {

// Half the cores, from 1 to 4 (batch_run.cpp says why).
int defaultBatchJobs();

// Every capture of the plan, `jobs` at once, in OUTDIR (created). progress(fraction of the
// captures finished) is called on the calling thread. Once cancellation is requested
// (parallel.hpp) no further capture starts; those are failed as cancelled.
Result<std::vector<BatchOutcome>> runBatchCaptures(const BatchPlan& plan, int jobs,
                                                   const ProgressCallback& progress = {});

// The report (docs/batch.md) as JSON text, also written atomically to plan.report.
Result<std::string> writeBatchReport(const BatchPlan& plan, const std::vector<BatchOutcome>& outcomes);

// Ok when no capture failed; otherwise an Io error "batch: F of N captures failed (... REPORT)".
Status batchStatus(const BatchPlan& plan, const std::vector<BatchOutcome>& outcomes);

const char* batchStatusName(BatchOutcome::Status status);  // "done", "skipped", "failed"

}  // namespace lfcam
