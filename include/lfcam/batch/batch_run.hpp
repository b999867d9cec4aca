// A whole batch on one machine, and its report: `lfcam batch`, lfcam.batch.run in Python, and, for
// the report, the same batch run on a Dask cluster (whose workers call runBatchCapture).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "lfcam/batch/batch_plan.hpp"
#include "lfcam/core/light_field.hpp"
#include "lfcam/core/progress.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/decode/decode.hpp"

namespace lfcam {

struct BatchOutcome {
  enum class Status { Done, Skipped, Failed } status = Status::Failed;
  std::vector<std::string> outputs;  // relative to OUTDIR
  double seconds = 0;
  std::string error;  // one line, naming the input
};

// One capture, as a cluster's worker runs it: its steps run on the light field read once, each
// output written atomically under OUTDIR/<name>/, then a done-marker written last. The marker
// records the steps and the size and modification time of the input and the white image or database (not
// their paths, so workers that see the same files under other names agree), so a rerun skips a
// capture only when these still match and every output is there; anything else is redone from the
// start. Idempotent: the same capture run twice, even at once, leaves each output old or whole; the
// single-machine batch and a Dask worker both call this, so their outputs are the same bytes.
// `white` (may be empty): the inputs are raw lenslet images, decoded on the way with it (batch_plan.hpp).
BatchOutcome runBatchCapture(const BatchCapture& capture, const std::vector<BatchStep>& steps, const BatchWhite& white,
                             const std::filesystem::path& outputFolder);

// A capture's light field: read, or decoded with `decode` when `white` names an image or a
// database (a hexagonal microscope's volume step decodes into bricks, as lfcam volume does).
Result<LightField> loadCapture(const std::filesystem::path& input, const BatchWhite& white,
                               const DecodeOptions& decode = {});

// The work every capture shares, done once in OUTDIR (created) before the captures are dispatched,
// here or to a cluster: each volume step's PSF cache (batchPsfPath) computed from the first capture
// that reads (the PSF depends on its pixels a lenslet), unless there already. Then every capture,
// in any process, only reads it: none computes it again, and none writes it while another reads.
// An error names the step and the capture.
Status prepareBatch(const BatchPlan& plan, const ProgressCallback& progress = {});

// Half the cores, from 1 to 4 (batch_run.cpp says why).
int defaultBatchJobs();

// Every capture of the plan, `jobs` at once, in OUTDIR (created), after prepareBatch. progress(fraction of the
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
