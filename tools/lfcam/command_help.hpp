// What `lfcam` says about its commands: the list printed by `lfcam` alone (one line each, as git
// does), the nearest command to a mistyped one, and the example that ends every command's --help.
#pragma once

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace lfcam::cli {

// Prints every subcommand of `app` with its one-line description.
void printCommandList(const CLI::App& app);

// The first argument that names a command, when it names none of app's: the command to blame in
// "unknown command 'foo'". Global options before it (and their values) are skipped.
std::optional<std::string> unknownCommand(const CLI::App& app, int argc, const char* const* argv);

// The subcommand whose name is closest to `name` (edit distance), for "did you mean".
std::string nearestCommand(const CLI::App& app, const std::string& name);

// Ends each subcommand's --help with an example run on the shared real data.
void addExamples(CLI::App& app);

}  // namespace lfcam::cli
