// The experiment by name.
#include "lfcam/experiments/experiments.hpp"

#include "experiments/experiment_support.hpp"

namespace lfcam {

std::vector<std::string> experimentNames() {
  return {"refocus-limit", "snr", "sharpness-vs-n", "fnumber-match", "observer-range"};
}

Status runExperiment(const std::string& name, const std::filesystem::path& folder, const ExperimentOptions& options) {
  using namespace experiments;
  if (name == "refocus-limit") return runRefocusLimit(folder, options);
  if (name == "snr") return runSnr(folder, options);
  if (name == "sharpness-vs-n") return runSharpnessVsN(folder, options);
  if (name == "fnumber-match") return runFNumberMatch(folder, options);
  if (name == "observer-range") return runObserverRange(folder, options);
  std::string names;
  for (const auto& n : experimentNames()) names += (names.empty() ? "" : ", ") + n;
  return makeError(ErrorCode::Usage, name + ": no such experiment (" + names + ")");
}

}  // namespace lfcam
