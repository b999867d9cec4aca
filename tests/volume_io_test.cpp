// Volume files: both formats round trip exactly, the TIFF carries what Fiji reads (checked with
// libtiff itself), foreign stacks read with their calibration, bad files are one clean error.
#include "lfcam/io/volume_io.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>  // to write and inspect HDF5 files by hand
#include <sys/resource.h>
#include <tiffio.h>

#include <cmath>
#include <csignal>
#include <cstdint>
#include <functional>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace lfcam::volume_test {
namespace {

namespace fs = std::filesystem;

Volume randomVolume(int width, int height, int depth, unsigned seed) {
  Volume volume(width, height, depth);
  std::mt19937 random(seed);
  std::normal_distribution<float> normal(0.0f, 3.0f);
  for (float& value : volume.voxels()) value = normal(random);
  volume.voxelWidthUm = 0.65;                        // no float, nor a short rational, holds these exactly
  volume.voxelHeightUm = 0.65 * std::sqrt(3.0) / 2;  // a hexagonal microlens array's
  volume.voxelDepthUm = 1.7;
  volume.firstSliceUm = -12.3;
  return volume;
}

void expectSameVolume(const Volume& read, const Volume& written) {
  ASSERT_EQ(read.width(), written.width());
  ASSERT_EQ(read.height(), written.height());
  ASSERT_EQ(read.depth(), written.depth());
  for (std::size_t i = 0; i < written.voxels().size(); ++i)
    ASSERT_EQ(read.voxels()[i], written.voxels()[i]) << "voxel " << i;
  EXPECT_EQ(read.voxelWidthUm, written.voxelWidthUm);
  EXPECT_EQ(read.voxelHeightUm, written.voxelHeightUm);
  EXPECT_EQ(read.voxelDepthUm, written.voxelDepthUm);
  EXPECT_EQ(read.firstSliceUm, written.firstSliceUm);
}

// The error is one line naming `path`, of `code`.
template <class T>
void expectErrorNaming(const Result<T>& result, const fs::path& path, ErrorCode code) {
  ASSERT_FALSE(result.ok()) << "expected an error naming " << path;
  EXPECT_EQ(result.error().code, code) << result.error().message;
  EXPECT_NE(result.error().message.find(path.string()), std::string::npos) << result.error().message;
  EXPECT_EQ(result.error().message.find('\n'), std::string::npos) << result.error().message;
}

std::set<std::string> namesIn(const fs::path& folder) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.insert(entry.path().filename().string());
  return names;
}

struct TiffCloser {
  void operator()(TIFF* tiff) const { TIFFClose(tiff); }
};
using TiffHandle = std::unique_ptr<TIFF, TiffCloser>;

// A TIFF of one 16-bit page per entry of `sizes` (width, height), codes from `code`, tagged by `tag`.
void writeCodeStack(const fs::path& path, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& sizes,
                    const std::function<std::uint16_t(std::uint32_t x, std::uint32_t y, int z)>& code,
                    const std::function<void(TIFF*, int z)>& tag) {
  TiffHandle tiff(TIFFOpen(path.c_str(), "w"));
  ASSERT_TRUE(tiff);
  for (int z = 0; z < int(sizes.size()); ++z) {
    const auto [width, height] = sizes[z];
    TIFFSetField(tiff.get(), TIFFTAG_IMAGEWIDTH, width);
    TIFFSetField(tiff.get(), TIFFTAG_IMAGELENGTH, height);
    TIFFSetField(tiff.get(), TIFFTAG_SAMPLESPERPIXEL, 1);
    TIFFSetField(tiff.get(), TIFFTAG_BITSPERSAMPLE, 16);
    TIFFSetField(tiff.get(), TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISBLACK);
    tag(tiff.get(), z);
    std::vector<std::uint16_t> row(width);
    for (std::uint32_t y = 0; y < height; ++y) {
      for (std::uint32_t x = 0; x < width; ++x) row[x] = code(x, y, z);
      ASSERT_GE(TIFFWriteScanline(tiff.get(), row.data(), y, 0), 0);
    }
    ASSERT_TRUE(TIFFWriteDirectory(tiff.get()));
  }
}

TEST(VolumeIo, TiffRoundTripIsExact) {
  test::TempDir dir;
  const Volume volume = randomVolume(37, 23, 5, 1);
  for (const char* name : {"stack.tif", "STACK.TIFF"}) {
    ASSERT_TRUE(writeVolume(dir / name, volume));
    auto read = readVolume(dir / name);
    ASSERT_TRUE(read) << read.error().message;
    expectSameVolume(*read, volume);
  }
}

TEST(VolumeIo, Hdf5RoundTripIsExact) {
  test::TempDir dir;
  const Volume volume = randomVolume(37, 23, 5, 2);
  for (const char* name : {"volume.h5", "volume.hdf5"}) {
    ASSERT_TRUE(writeVolume(dir / name, volume));
    auto read = readVolume(dir / name);
    ASSERT_TRUE(read) << read.error().message;
    expectSameVolume(*read, volume);
  }
}

TEST(VolumeIo, TiffCarriesImageJsStackAndVoxelSize) {
  test::TempDir dir;
  Volume volume = randomVolume(16, 12, 4, 3);
  volume.at(3, 2, 1) = -20.5f;  // the extremes, for min= and max=
  volume.at(5, 7, 3) = 40.25f;
  ASSERT_TRUE(writeVolume(dir / "stack.tif", volume));

  TiffHandle tiff(TIFFOpen((dir / "stack.tif").c_str(), "r"));
  ASSERT_TRUE(tiff);
  EXPECT_EQ(TIFFNumberOfDirectories(tiff.get()), 4u);
  char* description = nullptr;
  ASSERT_TRUE(TIFFGetField(tiff.get(), TIFFTAG_IMAGEDESCRIPTION, &description));
  EXPECT_EQ(std::string(description),
            "ImageJ=1.11a\nimages=4\nslices=4\nunit=micron\nspacing=1.7\nloop=false\nmin=-20.5\nmax=40.25\n"
            "lfcam_first_slice_um=-12.3\nlfcam_voxel_width_um=0.65\nlfcam_voxel_height_um=0.562916512459885\n");
  for (int z = 0; z < 4; ++z) {
    SCOPED_TRACE(z);
    ASSERT_TRUE(TIFFSetDirectory(tiff.get(), tdir_t(z)));
    std::uint16_t bits = 0, format = 0, channels = 0, unit = 0;
    std::uint32_t width = 0, height = 0;
    float x = 0, y = 0;
    TIFFGetField(tiff.get(), TIFFTAG_IMAGEWIDTH, &width);
    TIFFGetField(tiff.get(), TIFFTAG_IMAGELENGTH, &height);
    TIFFGetField(tiff.get(), TIFFTAG_BITSPERSAMPLE, &bits);
    TIFFGetField(tiff.get(), TIFFTAG_SAMPLESPERPIXEL, &channels);
    TIFFGetField(tiff.get(), TIFFTAG_SAMPLEFORMAT, &format);
    EXPECT_EQ(width, 16u);
    EXPECT_EQ(height, 12u);
    EXPECT_EQ(bits, 32);
    EXPECT_EQ(channels, 1);
    EXPECT_EQ(format, SAMPLEFORMAT_IEEEFP);
    ASSERT_TRUE(TIFFGetField(tiff.get(), TIFFTAG_XRESOLUTION, &x));
    ASSERT_TRUE(TIFFGetField(tiff.get(), TIFFTAG_YRESOLUTION, &y));
    ASSERT_TRUE(TIFFGetField(tiff.get(), TIFFTAG_RESOLUTIONUNIT, &unit));
    EXPECT_FLOAT_EQ(x, float(1 / 0.65));
    EXPECT_FLOAT_EQ(y, float(1 / volume.voxelHeightUm));  // Fiji's pixel height
    EXPECT_EQ(unit, RESUNIT_NONE);
    // ImageJ reads the description from the first page only.
    EXPECT_EQ(TIFFGetField(tiff.get(), TIFFTAG_IMAGEDESCRIPTION, &description), z == 0 ? 1 : 0);
  }
}

TEST(VolumeIo, ForeignStacksReadWithTheirCalibration) {
  test::TempDir dir;
  const auto code = [](std::uint32_t x, std::uint32_t y, int z) { return std::uint16_t(x * 1000 + y * 100 + z); };
  const std::vector<std::pair<std::uint32_t, std::uint32_t>> sizes(3, {9, 7});
  // Fiji's 16-bit stack in nanometres: 100 nm pixels, 250 nm slices.
  writeCodeStack(dir / "fiji.tif", sizes, code, [](TIFF* tiff, int z) {
    if (z == 0)
      TIFFSetField(tiff, TIFFTAG_IMAGEDESCRIPTION, "ImageJ=1.54f\nimages=3\nslices=3\nunit=nm\nspacing=250\n");
    TIFFSetField(tiff, TIFFTAG_XRESOLUTION, 0.01);
    TIFFSetField(tiff, TIFFTAG_YRESOLUTION, 0.01);
    TIFFSetField(tiff, TIFFTAG_RESOLUTIONUNIT, RESUNIT_NONE);
  });
  auto fiji = readVolume(dir / "fiji.tif");
  ASSERT_TRUE(fiji) << fiji.error().message;
  ASSERT_EQ(fiji->width(), 9);
  ASSERT_EQ(fiji->height(), 7);
  ASSERT_EQ(fiji->depth(), 3);
  EXPECT_FLOAT_EQ(fiji->at(8, 6, 2), float((8 * 1000 + 6 * 100 + 2) / 65535.0));
  EXPECT_NEAR(fiji->voxelWidthUm, 0.1, 1e-7);
  EXPECT_NEAR(fiji->voxelHeightUm, 0.1, 1e-7);
  EXPECT_DOUBLE_EQ(fiji->voxelDepthUm, 0.25);
  EXPECT_EQ(fiji->firstSliceUm, 0);

  // A microscope's stack with centimetre resolution and no ImageJ description; a bare one.
  writeCodeStack(dir / "microscope.tif", sizes, code, [](TIFF* tiff, int) {
    TIFFSetField(tiff, TIFFTAG_XRESOLUTION, 50000.0);
    TIFFSetField(tiff, TIFFTAG_YRESOLUTION, 50000.0);
    TIFFSetField(tiff, TIFFTAG_RESOLUTIONUNIT, RESUNIT_CENTIMETER);
  });
  writeCodeStack(dir / "bare.tif", sizes, code, [](TIFF*, int) {});
  auto microscope = readVolume(dir / "microscope.tif"), bare = readVolume(dir / "bare.tif");
  ASSERT_TRUE(microscope) << microscope.error().message;
  ASSERT_TRUE(bare) << bare.error().message;
  EXPECT_NEAR(microscope->voxelWidthUm, 0.2, 1e-7);
  EXPECT_EQ(microscope->voxelDepthUm, 1);
  EXPECT_EQ(bare->voxelWidthUm, 1);
  EXPECT_EQ(bare->voxelHeightUm, 1);
  EXPECT_EQ(bare->voxelDepthUm, 1);

  // An ImageJ hyperstack's pages interleave channels: not a volume's slices.
  writeCodeStack(dir / "channels.tif", sizes, code, [](TIFF* tiff, int z) {
    if (z == 0) TIFFSetField(tiff, TIFFTAG_IMAGEDESCRIPTION, "ImageJ=1.54f\nimages=3\nchannels=3\nhyperstack=true\n");
  });
  expectErrorNaming(readVolume(dir / "channels.tif"), dir / "channels.tif", ErrorCode::Unsupported);
}

TEST(VolumeIo, BadFilesAreOneCleanFormatError) {
  test::TempDir dir;
  test::writeBytes(dir / "text.tif", "not a TIFF at all");
  expectErrorNaming(readVolume(dir / "text.tif"), dir / "text.tif", ErrorCode::Format);

  writeCodeStack(
      dir / "sizes.tif", {{9, 7}, {9, 7}, {8, 7}}, [](std::uint32_t, std::uint32_t, int) { return 7; },
      [](TIFF*, int) {});
  auto sizes = readVolume(dir / "sizes.tif");
  expectErrorNaming(sizes, dir / "sizes.tif", ErrorCode::Format);
  EXPECT_NE(sizes.error().message.find("page 2 is 8x7"), std::string::npos) << sizes.error().message;

  // Cut anywhere: in the first page's samples, between pages, in the last directory.
  const Volume volume = randomVolume(40, 30, 6, 4);
  for (const char* name : {"cut.tif", "cut.h5"}) {
    ASSERT_TRUE(writeVolume(dir / name, volume));
    const std::string bytes = test::readBytes(dir / name);
    for (double fraction : {0.1, 0.5, 0.9, 0.999}) {
      SCOPED_TRACE(std::string(name) + " cut at " + std::to_string(fraction));
      test::writeBytes(dir / ("short-" + std::string(name)), bytes.substr(0, std::size_t(bytes.size() * fraction)));
      expectErrorNaming(readVolume(dir / ("short-" + std::string(name))), dir / ("short-" + std::string(name)),
                        ErrorCode::Format);
    }
  }

  // An HDF5 file of another layout.
  const fs::path other = dir / "other.h5";
  hid_t file = H5Fcreate(other.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t dims[3] = {2, 3, 4};
  hid_t space = H5Screate_simple(3, dims, nullptr);
  hid_t data = H5Dcreate2(file, "images", H5T_IEEE_F32LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dclose(data), H5Sclose(space), H5Fclose(file);
  auto wrongLayout = readVolume(other);
  expectErrorNaming(wrongLayout, other, ErrorCode::Format);
  EXPECT_NE(wrongLayout.error().message.find("no /volume dataset"), std::string::npos) << wrongLayout.error().message;
}

TEST(VolumeIo, RefusedWritesNameTheFile) {
  test::TempDir dir;
  const Volume volume = randomVolume(4, 3, 2, 5);
  const auto unknown = writeVolume(dir / "volume.png", volume);
  expectErrorNaming(unknown, dir / "volume.png", ErrorCode::Usage);
  expectErrorNaming(writeVolume(dir / "empty.tif", Volume()), dir / "empty.tif", ErrorCode::Usage);
  Volume flat = volume.copy();
  flat.voxelDepthUm = 0;
  expectErrorNaming(writeVolume(dir / "flat.h5", flat), dir / "flat.h5", ErrorCode::Usage);
  for (const char* name : {"stack.tif", "volume.h5"}) {
    const fs::path missing = dir / "missing" / name;
    const auto written = writeVolume(missing, volume);
    expectErrorNaming(written, missing, ErrorCode::Io);
    EXPECT_EQ(written.error().message,
              missing.string() + ": cannot write: the folder " + (dir / "missing").string() + " does not exist");
  }
  EXPECT_TRUE(namesIn(dir.path()).empty());
}

// A write that fails midway (the file-size limit stands for a full disk) leaves the old file whole
// and no temporary.
TEST(VolumeIo, AFailedWriteLeavesNoFileBehind) {
  test::TempDir dir;
  const Volume small = randomVolume(4, 3, 2, 6), large = randomVolume(200, 100, 8, 7);  // 640 kB of noise
  for (const char* name : {"stack.tif", "volume.h5"}) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(writeVolume(dir / name, small));
    const std::string before = test::readBytes(dir / name);
    rlimit saved{};
    ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &saved), 0);
    const auto previousHandler = std::signal(SIGXFSZ, SIG_IGN);  // EFBIG instead of a signal
    rlimit limited = saved;
    limited.rlim_cur = 64 << 10;
    ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &limited), 0);
    const Status written = writeVolume(dir / name, large);
    setrlimit(RLIMIT_FSIZE, &saved);
    std::signal(SIGXFSZ, previousHandler);
    expectErrorNaming(written, dir / name, ErrorCode::Io);
    EXPECT_EQ(test::readBytes(dir / name), before);
  }
  EXPECT_EQ(namesIn(dir.path()), (std::set<std::string>{"stack.tif", "volume.h5"}));
}

}  // namespace
}  // namespace lfcam::volume_test
