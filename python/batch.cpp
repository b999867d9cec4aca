// The C++ side of lfcam.batch (python/lfcam/batch.py): the plan, the single-machine run, one capture
// (what each Dask task calls) and the report, all the library's batch code (batch_run.hpp), so a
// capture's outputs are the same bytes whichever way it runs.
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "errors.hpp"
#include "interruptible.hpp"
#include "lfcam/batch/batch_run.hpp"
#include "progress.hpp"

namespace py = pybind11;

namespace lfcam::python {

namespace {

py::dict outcomeToDict(const BatchOutcome& outcome) {
  py::dict d;
  d["status"] = batchStatusName(outcome.status);
  d["outputs"] = outcome.outputs;
  d["seconds"] = outcome.seconds;
  d["error"] = outcome.error.empty() ? py::object(py::none()) : py::object(py::str(outcome.error));
  return d;
}

BatchOutcome outcomeFromDict(const py::dict& d) {
  BatchOutcome outcome;
  const std::string status = d["status"].cast<std::string>();
  outcome.status = status == "done"      ? BatchOutcome::Status::Done
                   : status == "skipped" ? BatchOutcome::Status::Skipped
                                         : BatchOutcome::Status::Failed;
  outcome.outputs = d["outputs"].cast<std::vector<std::string>>();
  outcome.seconds = d["seconds"].cast<double>();
  if (!d["error"].is_none()) outcome.error = d["error"].cast<std::string>();
  return outcome;
}

// The report's JSON text and, when a capture failed, the one-line message (None otherwise).
py::tuple finish(const BatchPlan& plan, const std::vector<BatchOutcome>& outcomes) {
  const std::string report = valueOrThrow(writeBatchReport(plan, outcomes));
  const Status status = batchStatus(plan, outcomes);
  return py::make_tuple(report, status ? py::object(py::none()) : py::object(py::str(status.error().message)));
}

}  // namespace

void bindBatch(py::module_& m) {
  py::class_<BatchPlan>(m, "_BatchPlan", "A checked batch: its captures, steps, output folder, white image, report.")
      .def_property_readonly("captures",
                             [](const BatchPlan& plan) {
                               std::vector<std::pair<std::string, std::string>> captures;
                               for (const BatchCapture& c : plan.captures) captures.emplace_back(c.input, c.name);
                               return captures;
                             })
      .def_property_readonly("steps",
                             [](const BatchPlan& plan) {
                               std::vector<std::string> texts;
                               for (const BatchStep& step : plan.steps) texts.push_back(step.text);
                               return texts;
                             })
      .def_property_readonly("output", [](const BatchPlan& plan) { return plan.output.string(); })
      .def_property_readonly("white", [](const BatchPlan& plan) { return plan.white.image.string(); })
      .def_property_readonly("whites", [](const BatchPlan& plan) { return plan.white.database.string(); })
      .def_property_readonly("any_camera", [](const BatchPlan& plan) { return plan.white.anyCamera; })
      .def_property_readonly("report", [](const BatchPlan& plan) { return plan.report.string(); });
  m.def("_split_batch_steps", &splitBatchSteps, "Steps from a comma-separated string (splitBatchSteps).");
  m.def(
      "_batch_plan",
      [](std::vector<std::string> inputs, std::string output, std::vector<std::string> steps, std::string white,
         std::string report, std::string whites, bool anyCamera) {
        return valueOrThrow(planBatch({.inputs = std::move(inputs),
                                       .steps = std::move(steps),
                                       .output = std::move(output),
                                       .white = std::move(white),
                                       .whites = std::move(whites),
                                       .report = std::move(report),
                                       .anyCamera = anyCamera}));
      },
      py::arg("inputs"), py::arg("output"), py::arg("steps"), py::arg("white"), py::arg("report"),
      py::arg("whites") = "", py::arg("any_camera") = false);
  m.def(
      "_batch_run_local",
      [](const BatchPlan& plan, int jobs, const py::object& progress) {
        const Progress report(progress, "batch.run");
        const auto outcomes = interruptible([&] {
          return valueOrThrow(runBatchCaptures(plan, jobs > 0 ? jobs : defaultBatchJobs(), report.callback()));
        });
        return finish(plan, outcomes);
      },
      py::arg("plan"), py::arg("jobs"), py::arg("progress"));
  m.def(
      "_batch_prepare", [](const BatchPlan& plan) { throwIfError(interruptible([&] { return prepareBatch(plan); })); },
      py::arg("plan"), "The work the captures share, once before they are dispatched (prepareBatch).");
  m.def(
      "_batch_capture",
      [](const std::string& input, const std::string& name, const std::vector<std::string>& stepTexts,
         const std::string& white, const std::string& output, const std::string& base, const std::string& whites,
         bool anyCamera) {
        const std::vector<BatchStep> steps = valueOrThrow(parseBatchSteps(stepTexts, base));
        const BatchWhite decoding{.image = white, .database = whites, .anyCamera = anyCamera};
        const BatchOutcome outcome =
            interruptible([&] { return runBatchCapture({.input = input, .name = name}, steps, decoding, output); });
        return outcomeToDict(outcome);
      },
      py::arg("input"), py::arg("name"), py::arg("steps"), py::arg("white"), py::arg("output"), py::arg("base") = "",
      py::arg("whites") = "", py::arg("any_camera") = false);
  m.def(
      "_batch_finish",
      [](const BatchPlan& plan, const std::vector<py::dict>& dicts) {
        std::vector<BatchOutcome> outcomes;
        for (const py::dict& d : dicts) outcomes.push_back(outcomeFromDict(d));
        return finish(plan, outcomes);
      },
      py::arg("plan"), py::arg("outcomes"));
}

}  // namespace lfcam::python
