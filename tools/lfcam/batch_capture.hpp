// One capture of `lfcam batch`: its steps run on the light field read once, each output written
// atomically under OUTDIR/<name>/, then the done-marker written last. The marker records the steps
// and the input's size and modification time, so a rerun skips a capture only when all three
// still match and every output is there; anything else is redone from the start.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "batch_plan.hpp"
#include "commands.hpp"

namespace lfcam::cli {

inline constexpr const char* kBatchDoneMarker = ".batch-done.json";

struct BatchOutcome {
  enum class Status { Done, Skipped, Failed } status = Status::Failed;
  std::vector<std::string> outputs;  // relative to OUTDIR
  double seconds = 0;
  std::string error;  // one line, naming the input
};

// `input` carries the decoding options (--white) shared by all captures; its path is ignored.
BatchOutcome runBatchCapture(const BatchCapture& capture, const std::vector<BatchStep>& steps,
                             const InputOptions& input, const std::filesystem::path& outputFolder);

}  // namespace lfcam::cli
