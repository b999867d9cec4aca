// The extension module lfcam._lfcam, re-exported by the package lfcam (python/lfcam/__init__.py).
#include <pybind11/pybind11.h>

#include "arrays.hpp"
#include "errors.hpp"

namespace py = pybind11;

namespace lfcam::python {

void bindPipeline(py::module_& module);
void bindPhotos(py::module_& module);
void bindSimulate(py::module_& module);
void bindBatch(py::module_& module);
void bindVolume(py::module_& module);
void bindFocused(py::module_& module);

void registerErrors(py::module_& m) {
  static py::exception<LibraryError> error(m, "Error", PyExc_RuntimeError);
  static py::exception<LibraryError> usage(m, "UsageError", error.ptr());
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const LibraryError& e) {
      (e.code == ErrorCode::Usage ? usage : error)(e.what());
    }
  });
}

}  // namespace lfcam::python

PYBIND11_MODULE(_lfcam, m) {
  m.doc() = "lfcam: light-field photography (Ng et al. 2005) from the C++ library.";
  lfcam::python::registerErrors(m);
  lfcam::python::bindArrays(m);
  lfcam::python::bindPipeline(m);
  lfcam::python::bindPhotos(m);
  lfcam::python::bindSimulate(m);
  lfcam::python::bindBatch(m);
  lfcam::python::bindVolume(m);
  lfcam::python::bindFocused(m);
}
