#include "dask_handover.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

namespace lfcam::cli {
namespace fs = std::filesystem;

namespace {

// One line and exit 1 rather than a traceback when the package or Dask cannot be imported.
constexpr const char* kBootstrap =
    "import sys\n"
    "try:\n"
    "    from lfcam.batch import main\n"
    "except ImportError as e:\n"
    "    sys.exit(f'lfcam: batch --dask: cannot import the Python package lfcam ({e}); build it (build/python) "
    "or put it on PYTHONPATH')\n"
    "sys.exit(main(sys.argv[1:]))\n";

std::string joined(const std::vector<std::string>& texts) {
  std::string all;
  for (const std::string& text : texts) all += (all.empty() ? "" : ",") + text;
  return all;
}

}  // namespace

Status handOverToDask(const BatchRequest& request, const std::string& scheduler) {
  std::error_code ec;
  const fs::path buildTree = fs::read_symlink("/proc/self/exe", ec).parent_path() / "python";
  if (!ec && fs::is_regular_file(buildTree / "lfcam" / "__init__.py")) {
    const char* previous = std::getenv("PYTHONPATH");
    const std::string path = buildTree.string() + (previous && *previous ? ":" + std::string(previous) : "");
    ::setenv("PYTHONPATH", path.c_str(), 1);
  }
  const char* fromEnvironment = std::getenv("LFCAM_PYTHON");
  const std::string python = fromEnvironment && *fromEnvironment ? fromEnvironment : LFCAM_PYTHON_EXECUTABLE;
  std::vector<std::string> arguments{python,         "-c",      kBootstrap,           "--dask", scheduler, "--output",
                                     request.output, "--steps", joined(request.steps)};
  if (!request.white.empty()) arguments.insert(arguments.end(), {"--white", request.white});
  if (!request.whites.empty()) arguments.insert(arguments.end(), {"--whites", request.whites});
  if (request.anyCamera) arguments.emplace_back("--any-camera");
  if (!request.report.empty()) arguments.insert(arguments.end(), {"--report", request.report});
  arguments.emplace_back("--");
  arguments.insert(arguments.end(), request.inputs.begin(), request.inputs.end());
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  argv.push_back(nullptr);
  std::fflush(nullptr);
  ::execvp(argv[0], argv.data());
  return makeError(ErrorCode::Io, "batch --dask: cannot run " + python + ": " + std::strerror(errno));
}

}  // namespace lfcam::cli
