// Start-up (docs/design.md, "Start-up"): the executable maps only the libraries every command may
// need; FFmpeg and LibRaw come in modules loaded on first use, and OpenImageIO is gone.
#include <gtest/gtest.h>

#include <cstdlib>

#include "cli_support.hpp"

namespace lfcam {
namespace {

TEST(StartUp, MapsNeitherFfmpegNorLibRawNorOpenImageIo) {
  test::TempDir dir;
  // The dynamic loader lists what it maps and stops, as ldd does.
  ASSERT_EQ(setenv("LD_TRACE_LOADED_OBJECTS", "1", 1), 0);
  const auto listed = test::runLfcam({"--help"}, dir.path());
  unsetenv("LD_TRACE_LOADED_OBJECTS");
  ASSERT_EQ(listed.exitStatus, 0) << listed.err;
  ASSERT_NE(listed.out.find("libstdc++"), std::string::npos) << listed.out;
  for (const char* heavy : {"libavcodec", "libavformat", "libswscale", "libraw", "libOpenImageIO", "libgdal"})
    EXPECT_EQ(listed.out.find(heavy), std::string::npos) << heavy << " is mapped at start-up:\n" << listed.out;
}

}  // namespace
}  // namespace lfcam
