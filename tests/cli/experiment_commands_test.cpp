// lfcam experiment NAME --quick: every report is written whole and its numbers are in range.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using test::runLfcam;

// Checks the report's files in `out`, returns results.json.
nlohmann::json readReport(const fs::path& out) {
  const std::string name = out.filename().string();
  for (const char* file : {"report.md", "report.html", "results.json"})
    EXPECT_TRUE(fs::exists(out / file)) << name << ": " << file;
  bool csv = false, plot = false;
  if (fs::exists(out))
    for (const auto& entry : fs::directory_iterator(out)) {
      csv |= entry.path().extension() == ".csv";
      plot |= entry.path().extension() == ".svg" || entry.path().extension() == ".png";
    }
  EXPECT_TRUE(csv) << name;
  EXPECT_TRUE(plot) << name;
  const std::string text = test::readBytes(out / "results.json");
  return nlohmann::json::parse(text, nullptr, false);
}

// Runs the experiment quickly, checks the report's files, returns results.json.
nlohmann::json runQuick(const std::string& name, const test::TempDir& dir) {
  const fs::path out = dir / name;
  const auto result = runLfcam({"experiment", name, "-o", out.string(), "--quick"}, dir.path());
  EXPECT_EQ(result.exitStatus, 0) << result.err;
  return readReport(out);
}

TEST(CliExperiment, RefocusLimitBeatsConventionalF4ByAWideMargin) {
  test::TempDir dir;
  const auto r = runQuick("refocus-limit", dir);
  ASSERT_TRUE(r.contains("matched_f_number") && r.contains("theory_f_number")) << r.dump();
  EXPECT_GE(r["matched_f_number"].get<double>(), 11);  // the quick run has 8 pixels per microlens: theory f/32
  EXPECT_GT(r["theory_f_number"].get<double>(), r["light_field_f_number"].get<double>());
  EXPECT_GT(r["cutoff_gain_over_f4"].get<double>(), 2);
  // Stopping down sharpens the conventional photo.
  const auto cutoffs = r["conventional_cutoffs"].get<std::vector<double>>();
  EXPECT_GT(cutoffs.back(), 2 * cutoffs.front());
  // Shift-and-add of the lined-up views is at least as sharp as the quadrilinear quadrature.
  ASSERT_TRUE(r.contains("light_field_cutoff_quadrature")) << r.dump();
  EXPECT_GE(r["light_field_cutoff"].get<double>(), r["light_field_cutoff_quadrature"].get<double>());
}

TEST(CliExperiment, SnrGrowsWithApertureAndTheLightFieldWins) {
  test::TempDir dir;
  const auto r = runQuick("snr", dir);
  ASSERT_TRUE(r.contains("snr_ratio") && r.contains("predicted_snr_ratio")) << r.dump();
  const auto snr = r["conventional_snr"].get<std::vector<double>>();  // f/4 ... f/22
  EXPECT_GT(snr.front(), 2 * snr.back());
  EXPECT_GT(r["snr_ratio"].get<double>(), 2);
  // Views added at whole-pixel shifts, no interpolation: the photon-noise law.
  EXPECT_NEAR(r["snr_ratio"].get<double>(), r["predicted_snr_ratio"].get<double>(),
              0.15 * r["predicted_snr_ratio"].get<double>());
  EXPECT_NEAR(r["predicted_snr_ratio"].get<double>(), 5.5, 1.0);  // sqrt((22 / 4)^2), less the aperture's corners
  // The quadrature method's interpolation averages noise: well above the law.
  EXPECT_GT(r["snr_ratio_quadrature"].get<double>(), 1.5 * r["snr_ratio"].get<double>());
}

// Section 4.2: refocused sharpness grows with the pixels under each microlens, close to a line.
// Run as the example of `lfcam experiment --help` (the quick run of this experiment) gives it.
TEST(CliExperiment, ExampleShowsSharpnessGrowingWithN) {
  test::TempDir dir;
  const auto words = test::helpExample("experiment", dir);
  ASSERT_GE(words.size(), 4u);
  ASSERT_EQ(words[2], "sharpness-vs-n");
  ASSERT_NE(std::find(words.begin(), words.end(), "--quick"), words.end());
  const auto output = std::find(words.begin(), words.end(), "-o");
  ASSERT_LT(output + 1, words.end());
  const auto result = test::runExample(words, dir);
  EXPECT_EQ(result.exitStatus, 0) << result.err;
  const auto r = readReport(dir / *(output + 1));
  ASSERT_TRUE(r.contains("slope") && r.contains("r2")) << r.dump();
  EXPECT_EQ(r["n"].size(), 4u);
  EXPECT_GT(r["slope"].get<double>(), 0);
  EXPECT_GT(r["r2"].get<double>(), 0.8);
  const auto cutoffs = r["cutoffs"].get<std::vector<double>>();  // N = 4 ... 10
  EXPECT_GT(cutoffs.back(), 1.5 * cutoffs.front());
}

TEST(CliExperiment, FNumberMatchFindsF4) {
  test::TempDir dir;
  const auto r = runQuick("fnumber-match", dir);
  ASSERT_TRUE(r.contains("diameter_over_pitch")) << r.dump();
  const auto ratio = r["diameter_over_pitch"].get<std::vector<double>>();  // f/2.8, f/4, f/8
  ASSERT_EQ(ratio.size(), 3u);
  EXPECT_GT(ratio[0], 1.2);
  EXPECT_NEAR(ratio[1], 1.0, 0.1);
  EXPECT_LT(ratio[2], 0.6);
  EXPECT_EQ(r["matched_f_number"].get<double>(), 4);
}

TEST(CliExperiment, ObserverRangeShrinksWithMagnification) {
  test::TempDir dir;
  const auto r = runQuick("observer-range", dir);
  ASSERT_TRUE(r.contains("lateral_range_over_distance")) << r.dump();
  const auto range = r["lateral_range_over_distance"].get<std::vector<double>>();
  ASSERT_EQ(range.size(), 2u);
  EXPECT_GT(range[0], 0);
  EXPECT_LT(range[1], range[0]);
}

TEST(CliExperiment, UnknownNameIsAUsageError) {
  test::TempDir dir;
  const auto result = runLfcam({"experiment", "nonsense", "-o", (dir / "x").string()}, dir.path());
  EXPECT_EQ(result.exitStatus, 2);
  EXPECT_EQ(result.errLines(), 1) << result.err;
  EXPECT_NE(result.err.find("refocus-limit"), std::string::npos) << result.err;
  EXPECT_FALSE(fs::exists(dir / "x"));
}

}  // namespace
}  // namespace lfcam
