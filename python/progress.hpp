// progress= of the long calls: None or False, no report; True, a tqdm bar (tqdm.auto: a widget in
// Jupyter) when tqdm can be imported, else none; a callable, called with the fraction done (0..1).
// The library reports from the thread the call runs on (interruptible.hpp), which takes the GIL for
// the callback alone. A callback's exception cannot stop the library: Python reports it as
// unraisable, as for any callback it cannot raise from, and the call goes on.
#pragma once

#include <pybind11/pybind11.h>

#include <string>

#include "lfcam/core/progress.hpp"

namespace lfcam::python {

class Progress {
 public:
  // With the GIL. `what` names the call, in the bar and in messages.
  Progress(const pybind11::object& progress, std::string what);
  // For the library, empty when there is nothing to report to. This object outlives the call.
  ProgressCallback callback() const;

 private:
  pybind11::object report_;  // called with the fraction; null: nothing to report to
  std::string what_;
};

}  // namespace lfcam::python
