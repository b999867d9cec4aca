// What the image-writing commands export at each --bit-depth: a low-contrast light field's views
// read back within a tight tolerance at 16 bits and exactly as floats, while 8-bit sRGB PNGs
// round it to a few dozen grey levels; every command honours the flag; bad depths write nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/io/light_field_io.hpp"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using test::runLfcam;

// Radiance between 0.3 and 0.5 of the white level, as a decoded raw of low contrast holds: smooth
// shading plus fine detail, different in every view and channel.
LightField lowContrastLightField() {
  LightField lightField({.nu = 5, .nv = 5, .ns = 40, .nt = 32, .channels = 3});
  for (int v = 0; v < 5; ++v)
    for (int u = 0; u < 5; ++u)
      for (int c = 0; c < 3; ++c)
        for (int t = 0; t < 32; ++t)
          for (int s = 0; s < 40; ++s) {
            const double shade = 0.5 + 0.25 * std::sin(0.11 * s + 0.7 * u + c) + 0.2 * std::cos(0.13 * t - 0.5 * v);
            const double detail = 0.05 * std::sin(1.7 * s * t + u - v + 3 * c);
            lightField.at(u, v, s, t, c) = float(0.3 + 0.2 * std::clamp(shade + detail, 0.0, 1.0));
          }
  return lightField;
}

// PSNR of `read` against `truth`, the peak being the white level (1); infinite when equal.
double psnr(const LightField& read, const LightField& truth) {
  double sum = 0;
  for (std::size_t i = 0; i < truth.samples().size(); ++i) {
    const double d = double(read.samples()[i]) - truth.samples()[i];
    sum += d * d;
  }
  return sum == 0 ? INFINITY : 10 * std::log10(double(truth.samples().size()) / sum);
}

TEST(CliExportDepth, LowContrastViewsReadBackAtSixteenBitsAndFloatButNotAtEight) {
  test::TempDir dir;
  const LightField truth = lowContrastLightField();
  const fs::path input = dir / "low.lf.h5";
  ASSERT_TRUE(writeLightField(input, truth));
  struct Case {
    std::vector<std::string> flags;
    double minPsnr, maxPsnr;
  };
  // 8-bit sRGB: about 40 codes span 0.3-0.5, steps of ~0.005; 16-bit: steps of 1/65535; float
  // views are the samples themselves.
  const std::vector<Case> cases = {{{}, 0, 60},
                                   {{"--bit-depth", "8"}, 0, 60},
                                   {{"--16bit"}, 95, 130},
                                   {{"--bit-depth", "16"}, 95, 130},
                                   {{"--format", "tif"}, 95, 130},
                                   {{"--format", "tif", "--bit-depth", "float"}, INFINITY, INFINITY},
                                   {{"--format", "exr"}, INFINITY, INFINITY}};
  int index = 0;
  for (const Case& c : cases) {
    const fs::path folder = dir / ("views" + std::to_string(index++));
    std::vector<std::string> args{"views", input.string(), "-o", folder.string()};
    args.insert(args.end(), c.flags.begin(), c.flags.end());
    const auto result = runLfcam(args, dir.path());
    ASSERT_EQ(result.exitStatus, 0) << result.err;
    auto read = readLightField(folder);
    ASSERT_TRUE(read) << read.error().message;
    ASSERT_EQ(read->shape(), truth.shape());
    const double figure = psnr(*read, truth);
    const std::set<float> levels(read->samples().begin(), read->samples().end());
    std::printf("[ export  ] views %s: PSNR %.2f dB against the light field (radiance 0.3-0.5), %zu distinct levels\n",
                testing::PrintToString(c.flags).c_str(), figure, levels.size());
    EXPECT_GE(figure, c.minPsnr) << testing::PrintToString(c.flags);
    EXPECT_LE(figure, c.maxPsnr) << testing::PrintToString(c.flags);
  }
}

// The same for a decoded simulator capture: what its exported views lose against the decoded
// light field itself, over the samples the decoder trusts (weight >= 0.5; views carry no weight).
// Decoded radiance leaves [0, 1] (interpolation overshoot at edges, patches brighter than the
// white image): integer files clamp it, so over all samples only float views keep everything;
// over the samples inside [0, 1], 16-bit views keep what 8-bit ones round away.
TEST(CliExportDepth, DecodedCaptureViewsKeepWhatTheLightFieldHolds) {
  test::TempDir dir;
  const std::string sim = (dir / "sim").string(), decoded = (dir / "decoded.lf.h5").string();
  ASSERT_EQ(runLfcam({"simulate", "chart", "--size", "160", "--samples", "1", "--noise", "off", "--no-ground-truth",
                      "-o", sim},
                     dir.path())
                .exitStatus,
            0);
  const auto decode = runLfcam({"decode", sim + "/raw.png", "--white", sim + "/white.png", "-o", decoded}, dir.path());
  ASSERT_EQ(decode.exitStatus, 0) << decode.err;
  auto truth = readLightField(decoded);
  ASSERT_TRUE(truth) << truth.error().message;
  const std::vector<std::vector<std::string>> depths = {
      {"--bit-depth", "8"}, {"--bit-depth", "16"}, {"--format", "exr", "--bit-depth", "float"}};
  std::vector<double> figures, inRangeFigures;
  for (const auto& flags : depths) {
    const fs::path folder = dir / ("views" + std::to_string(figures.size()));
    std::vector<std::string> args{"views", decoded, "-o", folder.string()};
    args.insert(args.end(), flags.begin(), flags.end());
    ASSERT_EQ(runLfcam(args, dir.path()).exitStatus, 0);
    auto read = readLightField(folder);
    ASSERT_TRUE(read) << read.error().message;
    double sum = 0, inRangeSum = 0, lowest = INFINITY, highest = -INFINITY;
    std::size_t count = 0, inRange = 0;
    for (int v = 0; v < truth->nv(); ++v)
      for (int u = 0; u < truth->nu(); ++u)
        for (int t = 0; t < truth->nt(); ++t)
          for (int s = 0; s < truth->ns(); ++s) {
            if (truth->weightPlane(u, v)[std::size_t(t) * truth->ns() + s] < 0.5f) continue;
            for (int c = 0; c < truth->channels(); ++c) {
              const double value = truth->at(u, v, s, t, c), d = read->at(u, v, s, t, c) - value;
              sum += d * d;
              lowest = std::min(lowest, value), highest = std::max(highest, value);
              ++count;
              if (value >= 0 && value <= 1) inRangeSum += d * d, ++inRange;
            }
          }
    ASSERT_GT(count, 0u);
    const auto decibels = [](double squares, std::size_t n) {
      return squares == 0 ? INFINITY : 10 * std::log10(double(n) / squares);
    };
    figures.push_back(decibels(sum, count));
    inRangeFigures.push_back(decibels(inRangeSum, inRange));
    std::printf(
        "[ export  ] decoded capture (radiance %.2f to %.2f), views %s: PSNR %.2f dB against the decoded "
        "light field; %.2f dB over the %.1f%% of samples inside [0, 1]\n",
        lowest, highest, testing::PrintToString(flags).c_str(), figures.back(), inRangeFigures.back(),
        100.0 * double(inRange) / double(count));
  }
  EXPECT_LT(inRangeFigures[0], 60);
  EXPECT_GT(inRangeFigures[1], 90);
  EXPECT_EQ(figures[2], INFINITY);
}

TEST(CliExportDepth, EveryImageCommandWritesTheDepthAsked) {
  test::TempDir dir;
  const std::string input = test::makeSynthLightField(dir, 5, 32).string();
  struct Case {
    std::vector<std::string> args;
    fs::path file;  // one image the command writes
    SampleType type;
  };
  const std::vector<Case> cases = {
      {{"refocus", input, "--slope", "0.5", "-o", (dir / "r.png").string(), "--bit-depth", "16"},
       dir / "r.png",
       SampleType::UInt16},
      {{"refocus", input, "--slope", "0.5", "-o", (dir / "r.tif").string(), "--bit-depth", "float"},
       dir / "r.tif",
       SampleType::Float32},
      {{"observer", input, "--u", "1", "--v", "0", "-o", (dir / "o.png").string(), "--bit-depth", "16"},
       dir / "o.png",
       SampleType::UInt16},
      {{"edof", input, "-o", (dir / "e.tif").string(), "--bit-depth", "8"}, dir / "e.tif", SampleType::UInt8},
      {{"stack", input, "--slopes", "-1:1:2", "--format", "tif", "--bit-depth", "float", "-o", (dir / "s").string()},
       dir / "s" / "slice_001.tif",
       SampleType::Float32},
      {{"animate", input, "--orbit", "--frames", "2", "--stills", "--bit-depth", "16", "-o", (dir / "a").string()},
       dir / "a" / "frame_001.png",
       SampleType::UInt16},
      {{"views", input, "--mosaic", (dir / "m.exr").string(), "-o", (dir / "v").string(), "--format", "exr"},
       dir / "m.exr",
       SampleType::Float32},
      {{"convert", input, "--layout", "rowcol", "--format", "tif", "--bit-depth", "8", "-o", (dir / "c").string()},
       dir / "c" / "view_01_01.tif",
       SampleType::UInt8},
  };
  for (const Case& c : cases) {
    const auto result = runLfcam(c.args, dir.path());
    ASSERT_EQ(result.exitStatus, 0) << testing::PrintToString(c.args) << ": " << result.err;
    auto header = readImageHeader(c.file);
    ASSERT_TRUE(header) << header.error().message;
    EXPECT_EQ(header->sampleType, c.type) << testing::PrintToString(c.args);
  }
  // The 16-bit and float files hold linear radiance: the same photograph as the float one.
  auto linear16 = readImage(dir / "r.png");
  auto linearFloat = readImage(dir / "r.tif");
  ASSERT_TRUE(linear16 && linearFloat);
  for (std::size_t i = 0; i < linearFloat->pixels().size(); ++i)
    ASSERT_NEAR(linear16->pixels()[i], std::clamp(linearFloat->pixels()[i], 0.0f, 1.0f), 0.5 / 65535 + 1e-7);
}

TEST(CliExportDepth, BadDepthsAreOneLineUsageErrorsAndWriteNothing) {
  test::TempDir dir;
  const std::string input = test::makeSynthLightField(dir, 5, 32).string();
  const std::string png = (dir / "x.png").string(), exr = (dir / "x.exr").string(), folder = (dir / "f").string();
  const std::vector<std::vector<std::string>> cases = {
      {"refocus", input, "--slope", "0", "-o", png, "--bit-depth", "12"},
      {"refocus", input, "--slope", "0", "-o", png, "--bit-depth", "float"},
      {"refocus", input, "--slope", "0", "-o", exr, "--bit-depth", "8"},
      {"refocus", input, "--slope", "0", "-o", (dir / "x.jpg").string(), "--bit-depth", "16"},
      {"observer", input, "--u", "0", "--v", "0", "-o", png, "--bit-depth", "float"},
      {"edof", input, "-o", exr, "--bit-depth", "16"},
      {"stack", input, "--slopes", "0:1:2", "--bit-depth", "float", "-o", folder},
      {"stack", input, "--slopes", "0:1:2", "--bit-depth", "half", "-o", folder},
      {"views", input, "--bit-depth", "float", "-o", folder},
      {"views", input, "--format", "exr", "--bit-depth", "16", "-o", folder},
      {"views", input, "--16bit", "--bit-depth", "16", "-o", folder},
      {"views", input, "--format", "jpg", "-o", folder},
      {"views", input, "--bit-depth", "16", "--mosaic", exr, "-o", folder},
      {"animate", input, "--orbit", "--stills", "--bit-depth", "float", "-o", folder},
      {"animate", input, "--orbit", "--bit-depth", "16", "-o", (dir / "a.gif").string()},
      {"convert", input, "--bit-depth", "float", "-o", folder},
      {"convert", input, "--bit-depth", "8", "-o", exr},
  };
  for (const auto& args : cases) {
    const auto result = runLfcam(args, dir.path());
    EXPECT_EQ(result.exitStatus, 2) << testing::PrintToString(args) << ": " << result.err;
    EXPECT_EQ(result.errLines(), 1) << testing::PrintToString(args) << ": " << result.err;
  }
  for (const char* name : {"x.png", "x.exr", "x.jpg", "f", "a.gif"}) EXPECT_FALSE(fs::exists(dir / name)) << name;
}

}  // namespace
}  // namespace lfcam
