// lfcam batch --dask ADDRESS: the batch handed to the Python package (`lfcam.batch`), which submits
// one task per capture to the Dask scheduler; each task calls the same runBatchCapture as a run on
// one machine. Dask lives in Python, so the command line replaces itself by python3 rather than
// speaking Dask's protocol.
#pragma once

#include <string>

#include "lfcam/batch/batch_plan.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam::cli {

// Replaces this process by `python3 -m lfcam.batch` with the request's flags; its exit status and
// messages are the batch's. The package is looked for beside this executable first (the build
// tree's build/python), then where python3 finds it (installed, or PYTHONPATH); LFCAM_PYTHON names
// another interpreter. Returns only when python3 cannot be started.
Status handOverToDask(const BatchRequest& request, const std::string& scheduler);

}  // namespace lfcam::cli
