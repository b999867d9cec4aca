// The progress= keyword (progress.hpp).
#include "progress.hpp"

#include <utility>

#include "errors.hpp"

namespace py = pybind11;

namespace lfcam::python {

Progress::Progress(const py::object& progress, std::string what) : what_(std::move(what)) {
  if (progress.is_none() || progress.ptr() == Py_False) return;
  if (progress.ptr() == Py_True) {
    py::object bar;
    try {
      bar = py::module_::import("tqdm.auto")
                .attr("tqdm")(py::arg("total") = 1.0, py::arg("desc") = what_,
                              py::arg("bar_format") = "{l_bar}{bar}| {elapsed}<{remaining}");
    } catch (py::error_already_set& e) {
      if (!e.matches(PyExc_ImportError)) throw;
      return;  // no tqdm, no bar
    }
    // The bar closes when it is dropped, with this object.
    report_ = py::cpp_function([bar](double fraction) { bar.attr("update")(fraction - bar.attr("n").cast<double>()); });
    return;
  }
  if (!PyCallable_Check(progress.ptr()))
    throw LibraryError(ErrorCode::Usage, what_ + ": progress must be a callable of the fraction done, True or None");
  report_ = progress;
}

ProgressCallback Progress::callback() const {
  if (!report_) return {};
  return [this](double fraction) {
    const py::gil_scoped_acquire acquire;
    try {
      report_(fraction);
    } catch (py::error_already_set& e) {
      e.discard_as_unraisable((what_ + "(progress=...)").c_str());
    }
  };
}

}  // namespace lfcam::python
