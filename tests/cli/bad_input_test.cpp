// Bad input never crashes lfcam: one line naming the file and the problem, exit status 1 (failed
// work) or 2 (wrong usage), no signal, and no output file left behind.
#include <gtest/gtest.h>
#include <hdf5.h>

#include "cli_support.hpp"
#include "lfcam/io/image_io.hpp"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using test::runLfcam;

struct BadInput {
  std::string name;
  std::function<fs::path(const test::TempDir&)> make;  // returns the bad input's path
  std::string mentioned;                               // what the message must name
};

// An HCI folder of 3x3 tiny views, written by lfcam, to be damaged by each case.
fs::path goodHciFolder(const test::TempDir& dir) {
  const fs::path folder = dir / "hci";
  auto made = runLfcam({"synth", "--views", "3", "--size", "16", "-o", folder.string()}, dir.path());
  EXPECT_EQ(made.exitStatus, 0) << made.err;
  return folder;
}

std::vector<BadInput> badInputs() {
  return {
      {"missing file", [](const test::TempDir& d) { return d / "nothing-here.lf.h5"; }, "nothing-here.lf.h5"},
      {"missing view",
       [](const test::TempDir& d) {
         fs::path folder = goodHciFolder(d);
         fs::remove(folder / "input_Cam004.png");
         return folder;
       },
       "input_Cam004"},
      {"mixed image sizes",
       [](const test::TempDir& d) {
         fs::path folder = goodHciFolder(d);
         fs::copy_file(folder / "input_Cam000.png", d / "keep.png");
         auto other = runLfcam({"synth", "--views", "1", "--size", "20", "-o", (d / "other.png").string()}, d.path());
         EXPECT_EQ(other.exitStatus, 0) << other.err;
         fs::copy_file(d / "other.png", folder / "input_Cam005.png", fs::copy_options::overwrite_existing);
         return folder;
       },
       "input_Cam005"},
      {"corrupt png",
       [](const test::TempDir& d) {
         fs::path folder = goodHciFolder(d);
         std::string bytes = test::readBytes(folder / "input_Cam007.png");
         test::writeBytes(folder / "input_Cam007.png", bytes.substr(0, bytes.size() / 2));
         return folder;
       },
       "input_Cam007"},
      {"garbage named like a light field",
       [](const test::TempDir& d) {
         test::writeBytes(d / "garbage.lf.h5", "this is not a light field\n");
         return d / "garbage.lf.h5";
       },
       "garbage.lf.h5"},
      {"hdf5 of another layout",
       [](const test::TempDir& d) {
         const fs::path path = d / "other-layout.h5";
         hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
         hsize_t dims[2] = {4, 4};
         hid_t space = H5Screate_simple(2, dims, nullptr);
         hid_t data = H5Dcreate2(file, "/images", H5T_NATIVE_FLOAT, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
         float zeros[16] = {};
         H5Dwrite(data, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, zeros);
         H5Dclose(data), H5Sclose(space), H5Fclose(file);
         return path;
       },
       "other-layout.h5"},
      {"empty folder",
       [](const test::TempDir& d) {
         fs::create_directories(d / "empty");
         return d / "empty";
       },
       "empty"},
  };
}

TEST(BadInput, EveryCommandFailsCleanly) {
  for (const BadInput& bad : badInputs()) {
    SCOPED_TRACE(bad.name);
    test::TempDir dir;
    const fs::path input = bad.make(dir);
    const fs::path out = dir / "out";
    const std::vector<std::vector<std::string>> commands = {
        {"info", input.string()},
        {"refocus", input.string(), "--slope", "0", "-o", out.string() + ".png"},
        {"convert", input.string(), "-o", out.string() + ".lf.h5"},
        {"views", input.string(), "-o", out.string() + "-views", "--mosaic", out.string() + ".jpg"},
    };
    for (const auto& command : commands) {
      const auto result = runLfcam(command, dir.path());
      EXPECT_EQ(result.signal, 0) << command[0];
      EXPECT_EQ(result.exitStatus, 1) << command[0] << ": " << result.err;
      EXPECT_EQ(result.errLines(), 1) << command[0] << ": " << result.err;
      EXPECT_NE(result.err.find(bad.mentioned), std::string::npos) << command[0] << ": " << result.err;
    }
    for (const char* suffix : {".png", ".lf.h5", "-views", ".jpg"})
      EXPECT_FALSE(fs::exists(out.string() + suffix)) << suffix;
    // Nothing else appeared next to the outputs (no temporaries left).
    for (const auto& entry : fs::directory_iterator(dir.path()))
      EXPECT_EQ(entry.path().filename().string().rfind(".lfcam-tmp", 0), std::string::npos) << entry.path();
  }
}

TEST(BadInput, UnwritableOutputLeavesNothing) {
  test::TempDir dir;
  auto made = runLfcam({"synth", "--views", "3", "--size", "16", "-o", (dir / "lf.lf.h5").string()}, dir.path());
  ASSERT_EQ(made.exitStatus, 0) << made.err;
  // Into a folder that does not exist.
  auto result = runLfcam(
      {"refocus", (dir / "lf.lf.h5").string(), "--slope", "0", "-o", (dir / "no-such-folder" / "out.png").string()},
      dir.path());
  EXPECT_EQ(result.exitStatus, 1) << result.err;
  EXPECT_EQ(result.errLines(), 1) << result.err;
  EXPECT_NE(result.err.find("no-such-folder"), std::string::npos) << result.err;
  // The same for a light field written by HDF5, in the name the user gave (not a temporary one).
  const fs::path missing = dir / "no-such-folder" / "x.lf.h5";
  result = runLfcam({"synth", "--views", "3", "--size", "16", "-o", missing.string()}, dir.path());
  EXPECT_EQ(result.exitStatus, 1) << result.err;
  EXPECT_EQ(result.err, "lfcam: " + missing.string() + ": cannot write: the folder " + missing.parent_path().string() +
                            " does not exist\n");
  EXPECT_FALSE(fs::exists(dir / "no-such-folder"));
  // A folder where a file is expected.
  fs::create_directories(dir / "a-folder.png");
  result = runLfcam({"refocus", (dir / "lf.lf.h5").string(), "--slope", "0", "-o", (dir / "a-folder.png").string()},
                    dir.path());
  EXPECT_NE(result.exitStatus, 0);
  EXPECT_EQ(result.errLines(), 1) << result.err;
  EXPECT_TRUE(fs::is_directory(dir / "a-folder.png"));
}

// A lenslet image without lfcam's description: views per lens that do not divide it are a usage
// error (status 2); so is an image in which no period stands out (it asks for the count).
TEST(BadInput, LensletViewsThatDoNotDivideTheImage) {
  test::TempDir dir;
  auto made = runLfcam({"synth", "--views", "5", "--size", "24", "-o", (dir / "lf.png").string()}, dir.path());
  ASSERT_EQ(made.exitStatus, 0) << made.err;
  auto image = readImage(dir / "lf.png");  // 120 x 120
  ASSERT_TRUE(image.ok());
  ASSERT_TRUE(writeImage(dir / "plain.png", *image).ok());  // the description dropped
  for (const char* views : {"7", "0"}) {
    const fs::path out = dir / "out.lf.h5";
    const auto result =
        runLfcam({"convert", (dir / "plain.png").string(), "--lenslet-views", views, "-o", out.string()}, dir.path());
    EXPECT_EQ(result.exitStatus, 2) << views << ": " << result.err;
    EXPECT_EQ(result.errLines(), 1) << result.err;
    EXPECT_NE(result.err.find(views == std::string("7") ? "plain.png" : "--lenslet-views"), std::string::npos)
        << result.err;
    EXPECT_FALSE(fs::exists(out));
  }
  const auto told = runLfcam({"info", (dir / "plain.png").string(), "--lenslet-views", "5"}, dir.path());
  EXPECT_EQ(told.exitStatus, 0) << told.err;
  // Without the count the views are found.
  const auto found = runLfcam({"info", (dir / "plain.png").string()}, dir.path());
  EXPECT_EQ(found.exitStatus, 0) << found.err;
  EXPECT_NE(found.out.find("5 x 5 views"), std::string::npos) << found.out;
}

}  // namespace
}  // namespace lfcam
