// `lfcam volume` as a user runs it: a small microscope frame (a lenslet image of 7 pixels a
// lenslet) to a TIFF stack of the grid's size, the PSF cached and read again, and one-line
// refusals (exit 2, no output) of what cannot be reconstructed.
#include <gtest/gtest.h>

#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <thread>
#include <tuple>

#include "cli_support.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/io/volume_io.hpp"

namespace lfcam {
namespace {

using test::runLfcam;

// A frame of 7 pixels a lenslet (6 x 5 lenslets unless asked), a bright spot under each lenslet's
// centre.
std::filesystem::path writeFrame(const test::TempDir& dir, int lensletsX = 6, int lensletsY = 5) {
  Image frame(lensletsX * 7, lensletsY * 7, 1);
  for (int y = 0; y < frame.height(); ++y)
    for (int x = 0; x < frame.width(); ++x) frame.at(x, y, 0) = (x % 7 == 3 && y % 7 == 3) ? 0.8f : 0.1f;
  const auto path = dir / "frame.tif";
  EXPECT_TRUE(writeImage(path, frame));
  return path;
}

// The flags of a small microscope, with `changed` flags given other values.
std::vector<std::string> smallMicroscope(const std::map<std::string, std::string>& changed = {}) {
  const std::pair<std::string, std::string> flags[] = {{"--lenslet-views", "7"},
                                                       {"--objective", "20x/0.5/water"},
                                                       {"--wavelength", "500"},
                                                       {"--pitch", "40"},
                                                       {"--microlens-focal-length", "800"},
                                                       {"--pixel-size", "5.714"},
                                                       {"--slices", "3"},
                                                       {"--um-per-slice", "3"},
                                                       {"--iterations", "2"},
                                                       {"--microlens-array", "square"}};
  std::vector<std::string> args;
  for (const auto& [flag, value] : flags) {
    args.push_back(flag);
    args.push_back(changed.count(flag) ? changed.at(flag) : value);
  }
  return args;
}

TEST(CliVolume, WritesAStackAndCachesItsPsf) {
  test::TempDir dir;
  const auto frame = writeFrame(dir);
  std::vector<std::string> args{
      "volume", frame.string(), "--psf", (dir / "psf.h5").string(), "-o", (dir / "volume.tif").string()};
  const auto microscope = smallMicroscope();
  args.insert(args.end(), microscope.begin(), microscope.end());
  for (const char* psf : {"computed into", "read from"}) {
    const auto result = runLfcam(args, dir.path());
    ASSERT_EQ(result.exitStatus, 0) << result.err;
    EXPECT_NE(result.out.find(std::string("PSF ") + psf), std::string::npos) << result.out;
    const auto volume = readVolume(dir / "volume.tif");
    ASSERT_TRUE(volume) << volume.error().message;
    EXPECT_EQ(volume->width(), 6);
    EXPECT_EQ(volume->height(), 5);
    EXPECT_EQ(volume->depth(), 3);
    EXPECT_NEAR(volume->voxelWidthUm, 2, 1e-9);  // 40 um / 20x, one voxel a lenslet
    EXPECT_NEAR(volume->voxelDepthUm, 3, 1e-9);
    EXPECT_NEAR(volume->firstSliceUm, -3, 1e-9);
  }
  // The cache refuses other optics rather than reconstruct with the wrong PSF.
  std::filesystem::remove(dir / "volume.tif");
  auto other = args;
  other.insert(other.end(), {"--tube-lens", "180"});
  const auto refused = runLfcam(other, dir.path());
  EXPECT_EQ(refused.exitStatus, 2) << refused.err;
  EXPECT_EQ(refused.errLines(), 1) << refused.err;
  EXPECT_NE(refused.err.find("psf.h5: made for tube lens focal length (mm) 200, not 180"), std::string::npos)
      << refused.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "volume.tif"));

  // A volume beyond the memory budget is refused before the work.
  std::vector<std::string> big{
      "volume", frame.string(), "--no-psf-cache", "--memory-limit", "64K", "-o", (dir / "volume.tif").string()};
  const auto deep = smallMicroscope({{"--slices", "400"}});  // 6 x 5 x 400 voxels, held six times
  big.insert(big.end(), deep.begin(), deep.end());
  const auto tooBig = runLfcam(big, dir.path());
  EXPECT_EQ(tooBig.exitStatus, 1) << tooBig.err;
  EXPECT_EQ(tooBig.errLines(), 1) << tooBig.err;
  EXPECT_NE(tooBig.err.find("more than the limit"), std::string::npos) << tooBig.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "volume.tif"));
}

TEST(CliVolume, ReconstructsAHexagonalFrameOnItsPeriod) {
  // 6 x 5 lenslets of a hexagonal array: rows in pairs, the fifth left out; voxels sqrt(3)/2 as high.
  test::TempDir dir;
  const auto frame = writeFrame(dir);
  const auto microscope = smallMicroscope({{"--microlens-array", "hexagonal"}});
  std::vector<Volume> volumes;
  for (const char* psf : {"computed into", "read from"}) {
    std::vector<std::string> args{
        "volume", frame.string(), "--psf", (dir / "psf.h5").string(), "-o", (dir / "volume.h5").string()};
    args.insert(args.end(), microscope.begin(), microscope.end());
    const auto result = runLfcam(args, dir.path());
    ASSERT_EQ(result.exitStatus, 0) << result.err;
    EXPECT_NE(result.out.find(psf), std::string::npos) << result.out;
    auto volume = readVolume(dir / "volume.h5");
    ASSERT_TRUE(volume) << volume.error().message;
    EXPECT_EQ(volume->width(), 6);
    EXPECT_EQ(volume->height(), 4);
    EXPECT_EQ(volume->depth(), 3);
    EXPECT_NEAR(volume->voxelWidthUm, 2, 1e-9);
    EXPECT_NEAR(volume->voxelHeightUm, std::sqrt(3.0), 1e-9);
    volumes.push_back(std::move(*volume));
  }
  EXPECT_TRUE(std::equal(volumes[0].voxels().begin(), volumes[0].voxels().end(), volumes[1].voxels().begin()));
  // A raw decoded on the way would be sampled on square pixels, not bricks: refused.
  std::vector<std::string> args{"volume", frame.string(), "--white", frame.string(), "-o", (dir / "raw.h5").string()};
  args.insert(args.end(), microscope.begin(), microscope.end());
  const auto refused = runLfcam(args, dir.path());
  EXPECT_EQ(refused.exitStatus, 2) << refused.err;
  EXPECT_EQ(refused.errLines(), 1) << refused.err;
  EXPECT_NE(refused.err.find("--white: a hexagonal array's raw is not decoded on the way"), std::string::npos)
      << refused.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "raw.h5"));
}

TEST(CliVolume, RefusesInOneLineWithNoOutput) {
  test::TempDir dir;
  const auto frame = writeFrame(dir);
  const auto out = (dir / "volume.tif").string();
  auto run = [&](const std::map<std::string, std::string>& changed, const std::string& output) {
    std::vector<std::string> args{"volume", frame.string(), "--no-psf-cache", "-o", output};
    const auto microscope = smallMicroscope(changed);
    args.insert(args.end(), microscope.begin(), microscope.end());
    return runLfcam(args, dir.path());
  };
  const std::tuple<std::map<std::string, std::string>, std::string, std::string> cases[] = {
      {{{"--slices", "0"}}, out, "slices 0 outside [1, 1000]"},
      {{{"--objective", "60/1.2/water"}}, out, "--objective: expected MAGx/NA/MEDIUM"},
      {{{"--objective", "60x/1.4/1.33"}}, out, "NA 1.4 above the immersion index 1.33"},
      {{{"--microlens-focal-length", "0"}}, out, "microlens focal length must be positive"},
      {{{"--pixel-size", "3"}}, out, "7 pixels a lenslet, but the optics give 13.3"},
      {{{"--microlens-array", "round"}}, out, "--microlens-array: expected square or hexagonal, got 'round'"},
      {{}, (dir / "volume.png").string(), "unknown volume extension '.png'"},
  };
  for (const auto& [changed, output, message] : cases) {
    const auto result = run(changed, output);
    EXPECT_NE(result.exitStatus, 0) << message;
    EXPECT_LE(result.exitStatus, 2) << message;
    EXPECT_EQ(result.errLines(), 1) << result.err;
    EXPECT_NE(result.err.find(message), std::string::npos) << result.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << message;
  }
}

TEST(CliVolume, CtrlCEndsTheIterationsAndWritesNothing) {
  test::TempDir dir;
  const auto frame = writeFrame(dir, 64, 64);
  std::vector<std::string> args{"volume", frame.string(), "--no-psf-cache", "-o", (dir / "volume.tif").string()};
  const auto microscope = smallMicroscope({{"--iterations", "10000"}});  // a minute or more, uninterrupted
  args.insert(args.end(), microscope.begin(), microscope.end());
  const pid_t pid = test::startLfcam(args, dir / "out.txt", dir / "err.txt");
  ASSERT_GT(pid, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by the signal instead of stopping";
  EXPECT_EQ(WEXITSTATUS(status), 1);
  const std::string err = test::readBytes(dir / "err.txt");
  EXPECT_NE(err.find("interrupted; nothing written"), std::string::npos) << err;
  EXPECT_FALSE(std::filesystem::exists(dir / "volume.tif"));
}

}  // namespace
}  // namespace lfcam
