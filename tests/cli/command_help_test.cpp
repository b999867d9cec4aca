// What lfcam says about its commands: the list printed by `lfcam` alone, the nearest command to a
// mistyped one, and the example ending every command's --help, each of which is run on the real
// data, here or by its command's tests (so an example that stops working fails a test).
#include <gtest/gtest.h>

#include <algorithm>

#include "cli/cli_support.hpp"

namespace lfcam::test {
namespace {

const std::vector<std::string> kCommands{"info",       "convert", "views",     "refocus", "stack",    "observer",
                                         "bench",      "animate", "synth",     "demo",    "simulate", "depth",
                                         "score",      "edof",    "denoise",   "extract", "view",     "export-html",
                                         "experiment", "decode",  "calibrate", "batch",   "volume",   "whites"};

TEST(CommandHelp, AloneListsEveryCommandOnOneLineEach) {
  TempDir dir;
  const auto result = runLfcam({}, dir.path());
  EXPECT_EQ(result.exitStatus, 2) << "no command is a usage error, as in git";
  EXPECT_EQ(result.err, "");
  for (const auto& command : kCommands)
    EXPECT_NE(result.out.find("\n  " + command + " "), std::string::npos) << command;
}

TEST(CommandHelp, UnknownCommandNamesTheNearest) {
  TempDir dir;
  const auto result = runLfcam({"--threads", "2", "refcous", "x.lf.h5"}, dir.path());
  EXPECT_EQ(result.exitStatus, 2);
  EXPECT_EQ(result.errLines(), 1) << result.err;
  EXPECT_NE(result.err.find("unknown command 'refcous'"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("'refocus'"), std::string::npos) << result.err;
}

TEST(CommandHelp, ViewHelpDescribesThePagesControls) {
  TempDir dir;
  const auto help = runLfcam({"view", "--help"}, dir.path());
  EXPECT_EQ(help.exitStatus, 0);
  for (const char* words : {"click a point", "Tilted", "three numbered points", "two-ended slider", "Finer grid (2x)"})
    EXPECT_NE(help.out.find(words), std::string::npos) << words;
  // The example still ends it.
  EXPECT_NE(help.out.find("Example (from the repository's root):\n  lfcam view"), std::string::npos);
}

TEST(CommandHelp, EveryCommandEndsWithAnExampleOfItself) {
  TempDir dir;
  for (const auto& command : kCommands) {
    const auto words = helpExample(command, dir);
    ASSERT_GE(words.size(), 2u) << command << " --help has no example";
    EXPECT_EQ(words[0], "lfcam");
    EXPECT_EQ(words[1], command);
  }
}

// Each example runs. Not here: `view` serves until stopped (the viewer's own tests run it); the
// examples of `demo` and `experiment` are run by those commands' tests, which also check what they
// write (commands_test.cpp, experiment_commands_test.cpp), so that none runs twice; `whites` needs
// Lytro calibration data, of which the real data holds only metadata (whites_command_test.cpp runs
// it on simulated calibration data).
class CommandExample : public ::testing::TestWithParam<std::string> {};

TEST_P(CommandExample, RunsFromTheRepositorysRoot) {
  TempDir dir;
  const auto words = helpExample(GetParam(), dir);
  ASSERT_GE(words.size(), 2u) << GetParam() << " --help has no example";
  const bool needsData = std::any_of(
      words.begin(), words.end(), [](const std::string& word) { return word.rfind(sharedDataDir().string(), 0) == 0; });
  if (needsData && !std::filesystem::exists(sharedDataDir()))
    GTEST_SKIP() << "real data not found at " << sharedDataDir() << " (set LFCAM_DATA_DIR to run this example)";
  const auto result = runExample(words, dir);
  EXPECT_EQ(result.exitStatus, 0) << GetParam() << ": " << result.err;
}

std::vector<std::string> commandsWhoseExampleRunsHere() {
  std::vector<std::string> commands;
  for (const auto& command : kCommands)
    if (command != "view" && command != "demo" && command != "experiment" && command != "whites")
      commands.push_back(command);
  return commands;
}

INSTANTIATE_TEST_SUITE_P(EveryCommand, CommandExample, ::testing::ValuesIn(commandsWhoseExampleRunsHere()),
                         [](const auto& instance) {
                           std::string name = instance.param;
                           for (char& c : name) c = c == '-' ? '_' : c;
                           return name;
                         });

}  // namespace
}  // namespace lfcam::test
