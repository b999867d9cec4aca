// One capture of a batch: its steps run on the light field read once, each output written
// atomically under OUTDIR/<name>/, then the done-marker written last. The marker records the steps
// and the size and modification time of the input and the white image (not their paths, so a
// cluster's workers that see the same files under other names agree), so a rerun skips a capture
// only when these still match and every output is there; anything else is redone from the start.
// Idempotent: the same capture run twice, even at once, leaves each output old or whole; the
// single-machine batch and a Dask worker both call this, so their outputs are the same bytes.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "lfcam/batch_plan.hpp"

namespace lfcam {

inline constexpr const char* kBatchDoneMarker = ".batch-done.json";

struct BatchOutcome {
  enum class Status { Done, Skipped, Failed } status = Status::Failed;
  std::vector<std::string> outputs;  // relative to OUTDIR
  double seconds = 0;
  std::string error;  // one line, naming the input
};

// `white` (may be empty): the inputs are raw lenslet images of this white image, decoded on the way.
BatchOutcome runBatchCapture(const BatchCapture& capture, const std::vector<BatchStep>& steps,
                             const std::filesystem::path& white, const std::filesystem::path& outputFolder);

}  // namespace lfcam
