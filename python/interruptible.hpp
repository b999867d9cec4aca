// Long library calls from Python: run without the GIL (other Python threads go on) and stop soon
// on Ctrl-C. The call runs on a worker thread while the calling thread waits, taking the GIL every
// 50 ms to let Python handle signals; on KeyboardInterrupt it requests cancellation
// (parallel.hpp), waits for the call to give up, discards its result and raises.
#pragma once

#include <pybind11/pybind11.h>

#include <chrono>
#include <exception>
#include <future>
#include <optional>
#include <type_traits>
#include <utility>

#include "core/parallel.hpp"

namespace lfcam::python {

template <class F>
auto interruptible(F&& call) -> std::invoke_result_t<F> {
  using T = std::invoke_result_t<F>;
  bool interrupted = false;
  std::future<T> done;
  {
    pybind11::gil_scoped_release release;
    done = std::async(std::launch::async, std::forward<F>(call));
    while (done.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready) {
      if (interrupted) continue;
      pybind11::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() != 0) {  // the KeyboardInterrupt stays set for the raise below
        interrupted = true;
        requestCancellation(true);
      }
    }
  }
  if (interrupted) {
    requestCancellation(false);
    try {
      (void)done.get();
    } catch (...) {  // a cancelled call's error is as meaningless as its result
    }
    throw pybind11::error_already_set();
  }
  return done.get();
}

}  // namespace lfcam::python
