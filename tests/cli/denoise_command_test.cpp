// `lfcam denoise` as a user runs it: a filtered light field of the input's shape, with or without
// --depth-range, and one-line usage errors (exit 2, no output file) for a bad range.
#include <gtest/gtest.h>

#include "cli_support.hpp"
#include "lfcam/io/light_field_io.hpp"

namespace lfcam {
namespace {

using test::runLfcam;

TEST(CliDenoise, WritesAFilteredLightFieldOfTheSameShape) {
  test::TempDir dir;
  const auto input = test::makeSynthLightField(dir);
  for (const std::vector<std::string>& range : {std::vector<std::string>{}, {"--depth-range", "-1:1.6"}}) {
    std::vector<std::string> args{"denoise", input.string(), "-o", (dir / "out.lf.h5").string()};
    args.insert(args.end(), range.begin(), range.end());
    const auto result = runLfcam(args, dir.path());
    ASSERT_EQ(result.exitStatus, 0) << result.err;
    auto in = readLightField(input);
    auto out = readLightField(dir / "out.lf.h5");
    ASSERT_TRUE(in && out);
    EXPECT_EQ(out->shape(), in->shape());
    double change = 0;
    for (std::size_t i = 0; i < in->samples().size(); ++i)
      change = std::max(change, double(std::abs(in->samples()[i] - out->samples()[i])));
    EXPECT_GT(change, 1e-3) << "the filter changed nothing";
  }
}

TEST(CliDenoise, BadRangeIsAOneLineUsageErrorWithNoOutput) {
  test::TempDir dir;
  const auto input = test::makeSynthLightField(dir);
  for (const std::string range : {"1:0", "1", "a:b", "0:nan"}) {
    const auto result =
        runLfcam({"denoise", input.string(), "--depth-range", range, "-o", (dir / "out.lf.h5").string()}, dir.path());
    EXPECT_EQ(result.exitStatus, 2) << range << ": " << result.err;
    EXPECT_EQ(result.errLines(), 1) << result.err;
    EXPECT_NE(result.err.find("--depth-range"), std::string::npos) << result.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.lf.h5"));
  }
  const auto bandwidth =
      runLfcam({"denoise", input.string(), "--bandwidth", "0", "-o", (dir / "out.lf.h5").string()}, dir.path());
  EXPECT_EQ(bandwidth.exitStatus, 2) << bandwidth.err;
  EXPECT_EQ(bandwidth.errLines(), 1) << bandwidth.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.lf.h5"));
}

}  // namespace
}  // namespace lfcam
