// lfcam's errors as Python exceptions: lfcam.UsageError (ErrorCode::Usage) and lfcam.Error (the
// rest), with the library's one-line message, the same as the command line prints.
#pragma once

#include <pybind11/pybind11.h>

#include <stdexcept>
#include <utility>

#include "lfcam/core/result.hpp"

namespace lfcam::python {

struct LibraryError : std::runtime_error {
  LibraryError(ErrorCode code, const std::string& message) : std::runtime_error(message), code(code) {}
  ErrorCode code;
};

// The value, or the error thrown as a LibraryError (translated by registerErrors).
template <class T>
T valueOrThrow(Result<T>&& result) {
  if (!result) throw LibraryError(result.error().code, result.error().message);
  return std::move(*result);
}
inline void throwIfError(const Status& status) {
  if (!status) throw LibraryError(status.error().code, status.error().message);
}

void registerErrors(pybind11::module_& module);

}  // namespace lfcam::python
