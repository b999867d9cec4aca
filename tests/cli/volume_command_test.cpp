// `lfcam volume` as a user runs it: a small microscope frame (a lenslet image of 7 pixels a
// lenslet) to a TIFF stack of the grid's size, the PSF cached and read again, a hexagonal array's
// raw decoded on the way, and one-line refusals (exit 2, no output) of what cannot be reconstructed.
#include <gtest/gtest.h>

#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <thread>
#include <tuple>

#include "cli_support.hpp"
#include "lfcam/decode/decode_files.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/io/volume_io.hpp"
#include "lfcam/lfm/projector.hpp"
#include "lfcam/lfm/sparse_psf.hpp"
#include "lfcam/lfm/volume_request.hpp"

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
                                                       {"--microlens-array", "square"},
                                                       {"--supersample", "1"}};
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
}

// Catmull-Rom's weights of the taps at -1, 0, 1, 2 for a sample at fraction f.
std::array<double, 4> catmullRom(double f) {
  return {f * (-0.5 + f * (1 - 0.5 * f)), 1 + f * f * (-2.5 + 1.5 * f), f * (0.5 + f * (2 - 1.5 * f)),
          f * f * (-0.5 + 0.5 * f)};
}

// A camera's view of a rectified hexagonal frame (7 pixels a lenslet): its square pixels of a
// lenslet's pitch / 7, the lattice turned by 0.4 degrees, its top row of lenslets (an unshifted
// one) left out so that the camera's first row is a shifted one. The frame's bricks are
// interpolated (Catmull-Rom along its pixel rows, each at its own row's shift, then across them).
Image cameraView(const Image& frame) {
  constexpr int n = 7;
  const double pitch = n, rowPitch = pitch * std::sqrt(3.0) / 2, turn = 0.4 * M_PI / 180;
  const double originX = 4.3, originY = 5.6 - rowPitch;  // lenslet (0, 0)'s centre, raw pixels
  auto at = [&](int x, int r) {
    return x >= 0 && x < frame.width() && r >= n && r < frame.height() ? frame.at(x, r, 0) : 0.0f;
  };
  Image raw(78, 61, 1);
  for (int y = 0; y < raw.height(); ++y)
    for (int x = 0; x < raw.width(); ++x) {
      const double dx = x + 0.5 - originX, dy = y + 0.5 - originY;
      const double a = std::cos(turn) * dx + std::sin(turn) * dy, b = -std::sin(turn) * dx + std::cos(turn) * dy;
      const double row = (b / rowPitch + 0.5) * n - 0.5;
      const int r0 = int(std::floor(row));
      const auto wy = catmullRom(row - r0);
      double value = 0;
      for (int k = 0; k < 4; ++k) {
        const int r = r0 - 1 + k;
        const int t = int(std::floor(double(r) / n));
        const double column = (a / pitch - (t % 2 != 0 ? 0.5 : 0.0) + 0.5) * n - 0.5;
        const int c0 = int(std::floor(column));
        const auto wx = catmullRom(column - c0);
        for (int m = 0; m < 4; ++m) value += wy[std::size_t(k)] * wx[std::size_t(m)] * at(c0 - 1 + m, r);
      }
      raw.at(x, y, 0) = float(std::clamp(value, 0.0, 1.0));
    }
  return raw;
}

TEST(CliVolume, DecodesAHexagonalRawIntoItsBricks) {
  // The forward model's frames of a bead and of a uniform specimen (the white image), rectified
  // on 10 x 10 lenslets, and a camera's raw and white image of them (cameraView) over an offset its
  // dark frame holds: the raw decoded on the way is the frame again and its bead lands where the
  // frame's does.
  // Two voxels a lenslet: a uniform volume's voxels then lie symmetric about every lenslet, as a
  // white image's light does (with one, half a pitch off the shifted rows', whose images calibration
  // then does not take for lenslets).
  test::TempDir dir;
  const auto microscope =
      smallMicroscope({{"--microlens-array", "hexagonal"}, {"--iterations", "10"}, {"--supersample", "2"}});
  auto request = volumeRequestFrom({.objective = "20x/0.5/water",
                                    .microlensArray = "hexagonal",
                                    .wavelengthNm = 500,
                                    .pitchUm = 40,
                                    .microlensFocalLengthUm = 800,
                                    .pixelSizeUm = 5.714,
                                    .umPerSlice = 3,
                                    .slices = 3,
                                    .supersample = 2});
  ASSERT_TRUE(request) << request.error().message;
  request->psfPath = (dir / "psf.h5").string();
  constexpr int n = 7, lenslets = 10;
  ASSERT_TRUE(cacheVolumePsf(LightField(LightFieldShape{n, n, lenslets, lenslets, 1}), *request, "frame"));
  const auto psf =
      readPsfCache(request->psfPath, request->optics,
                   {.pixelsPerLenslet = n, .voxelsPerLenslet = 2, .depthsUm = request->depthsUm()}, request->psfEnergy);
  ASSERT_TRUE(psf) << psf.error().message;
  const LfmProjector projector(psf.value(), lenslets, lenslets);
  Volume bead = projector.emptyVolume(), uniform = projector.emptyVolume();
  bead.at(10, 10, 0) = 1;
  std::fill(uniform.voxels().begin(), uniform.voxels().end(), 1.0f);
  auto normalised = [](Image image) {
    const float peak = *std::max_element(image.pixels().begin(), image.pixels().end());
    for (float& p : image.pixels()) p /= peak;
    return image;
  };
  const Image frame = normalised(projector.forward(bead)), white = normalised(projector.forward(uniform));
  ASSERT_TRUE(writeImage(dir / "frame.tif", frame));
  // The camera's offset, which the dark frame holds.
  auto offset = [](Image image) {
    for (float& p : image.pixels()) p = 0.02f + 0.95f * p;
    return image;
  };
  const Image dark = offset(Image(78, 61, 1));
  ASSERT_TRUE(writeImage(dir / "raw.png", offset(cameraView(frame)), {.sampleType = SampleType::UInt16}));
  ASSERT_TRUE(writeImage(dir / "white.png", offset(cameraView(white)), {.sampleType = SampleType::UInt16}));
  ASSERT_TRUE(writeImage(dir / "dark.png", dark, {.sampleType = SampleType::UInt16}));

  // Decoded as lfcam volume decodes it: the camera's first row (shifted) left out, the frame's
  // rows from 2 on. Its radiance times its weight is the raw over the white's brightest.
  const std::string raw = (dir / "raw.png").string(), whiteFile = (dir / "white.png").string(),
                    darkFile = (dir / "dark.png").string();
  RawFiles files{.raw = raw, .white = whiteFile, .dark = darkFile};
  files.decode.sampling = Sampling::Bricks;
  const auto decoded = decodeRawFiles(files);
  ASSERT_TRUE(decoded) << decoded.error().message;
  ASSERT_EQ(decoded->shape(), (LightFieldShape{n, n, lenslets, lenslets - 2, 1}));
  double dot = 0, norm = 0;
  std::vector<std::pair<double, double>> pairs;
  for (int t = 0; t < decoded->nt(); ++t)
    for (int s = 0; s < decoded->ns(); ++s)
      for (int v = 0; v < n; ++v)
        for (int u = 0; u < n; ++u) {
          const double value = decoded->at(u, v, s, t, 0) * decoded->weightPlane(u, v)[std::size_t(t) * lenslets + s];
          const double truth = frame.at(s * n + u, (t + 2) * n + v, 0);
          pairs.emplace_back(value, truth);
          dot += value * truth, norm += value * value;
        }
  double error = 0, energy = 0;
  for (const auto& [value, truth] : pairs) error += std::pow(dot / norm * value - truth, 2), energy += truth * truth;
  const double relative = std::sqrt(error / energy);
  std::printf("decoded frame against the rectified one: relative RMS %.4f\n", relative);
  EXPECT_LT(relative, 0.1);

  // The bead's centroid (over the brightest voxel's neighbours) from each.
  auto centroid = [&](const std::filesystem::path& volumeFile, std::vector<std::string> args) {
    args.insert(args.end(), {"--psf", request->psfPath, "-o", volumeFile.string()});
    args.insert(args.end(), microscope.begin(), microscope.end());
    const auto result = runLfcam(args, dir.path());
    EXPECT_EQ(result.exitStatus, 0) << result.err;
    EXPECT_NE(result.out.find("PSF read from"), std::string::npos) << result.out;
    const auto volume = readVolume(volumeFile);
    EXPECT_TRUE(volume) << volume.error().message;
    const auto& voxels = volume->voxels();
    const auto peak = std::size_t(std::max_element(voxels.begin(), voxels.end()) - voxels.begin());
    const int w = volume->width(), h = volume->height(), px = int(peak % w), py = int(peak / w % h),
              pz = int(peak / w / h);
    std::array<double, 4> sum{};
    for (int z = std::max(0, pz - 1); z <= std::min(volume->depth() - 1, pz + 1); ++z)
      for (int y = std::max(0, py - 1); y <= std::min(h - 1, py + 1); ++y)
        for (int x = std::max(0, px - 1); x <= std::min(w - 1, px + 1); ++x) {
          const double value = volume->at(x, y, z);
          sum[0] += value * x, sum[1] += value * y, sum[2] += value * z, sum[3] += value;
        }
    return std::array<double, 3>{sum[0] / sum[3], sum[1] / sum[3], sum[2] / sum[3]};
  };
  const auto fromFrame = centroid(dir / "frame.h5", {"volume", (dir / "frame.tif").string()});
  const auto fromRaw = centroid(dir / "raw.h5", {"volume", raw, "--white", whiteFile, "--dark", darkFile});
  std::printf("bead (10, 10, 0): centroid (%.2f, %.2f, %.2f) from the frame, (%.2f, %.2f + 4, %.2f) from the raw\n",
              fromFrame[0], fromFrame[1], fromFrame[2], fromRaw[0], fromRaw[1], fromRaw[2]);
  EXPECT_LT(std::abs(fromRaw[0] - fromFrame[0]), 1);
  EXPECT_LT(std::abs(fromRaw[1] + 4 - fromFrame[1]), 1);  // two rows of lenslets, two voxels each
  EXPECT_LT(std::abs(fromRaw[2] - fromFrame[2]), 1);

  // lfcam batch's volume step decodes it as lfcam volume does (a batch takes no dark frame), from
  // the same PSF.
  const std::filesystem::path out = dir / "out";
  std::filesystem::create_directories(out);
  std::filesystem::copy_file(request->psfPath, out / psfCacheName(*request));
  test::writeBytes(dir / "optics.json", R"({"calibrate": {"objective_magnification": 20, "objective_na": 0.5,
      "medium_index": 1.333, "center_wavelength": 500, "ulens_pitch": 40, "ulens_focal_length": 800,
      "pixel_size": 5.714, "ulens_array": "hexagonal", "num_slices": 3, "um_per_slice": 3, "supersample": 2},
      "deconvolve": {"max_iter": 10}})");
  const auto batch = runLfcam(
      {"batch", raw, "--white", whiteFile, "-o", out.string(), "--steps", "volume:" + (dir / "optics.json").string()},
      dir.path());
  ASSERT_EQ(batch.exitStatus, 0) << batch.err;
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(out), {}), 3) << "the PSF, the capture, the report";
  std::vector<std::string> single{
      "volume", raw, "--white", whiteFile, "--psf", request->psfPath, "-o", (dir / "single.tif").string()};
  single.insert(single.end(), microscope.begin(), microscope.end());
  ASSERT_EQ(runLfcam(single, dir.path()).exitStatus, 0);
  const auto fromBatch = readVolume(out / "raw" / "volume.tif"), fromSingle = readVolume(dir / "single.tif");
  ASSERT_TRUE(fromBatch && fromSingle);
  EXPECT_TRUE(std::equal(fromBatch->voxels().begin(), fromBatch->voxels().end(), fromSingle->voxels().begin(),
                         fromSingle->voxels().end()));

  // Sampled as the paper's integral pitch, it would not be the bricks; a square array's optics do
  // not describe its lattice: refused.
  const std::pair<std::map<std::string, std::string>, std::string> refusals[] = {
      {{{"--microlens-array", "hexagonal"}, {"--sampling", "integral"}},
       "--sampling integral: a hexagonal array's raw is sampled on its bricks"},
      {{{"--microlens-array", "square"}},
       "raw.png: decode: the lenslet grid is hexagonal, not the square array expected"}};
  for (const auto& [changed, message] : refusals) {
    std::vector<std::string> args{"volume", raw, "--white", whiteFile, "-o", (dir / "no.h5").string()};
    const auto flags = smallMicroscope(changed);
    args.insert(args.end(), flags.begin(), flags.end());
    if (changed.count("--sampling")) args.insert(args.end(), {"--sampling", changed.at("--sampling")});
    const auto refused = runLfcam(args, dir.path());
    EXPECT_EQ(refused.exitStatus, 2) << refused.err;
    EXPECT_EQ(refused.errLines(), 1) << refused.err;
    EXPECT_NE(refused.err.find(message), std::string::npos) << refused.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "no.h5"));
  }
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
