// A corpus of malformed inputs, each made here from small files lfcam writes, each run through the
// CLI. Every one must fail cleanly: no signal, exit status 1 or 2, exactly one line
// `lfcam: ...` naming the bad file, and the case's folder exactly as before (inputs unchanged, no
// output and no temporary left behind). bad_input_test.cpp runs a few inputs through every
// command; this file covers the many ways one input can be bad.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <map>

#include "cli_support.hpp"
#include "lfcam/io/image_io.hpp"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using test::readBytes;
using test::runLfcam;
using test::writeBytes;

// Small valid inputs, made once by lfcam itself.
class BadInputCorpus : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    base_ = new test::TempDir;
    const fs::path b = base_->path();
    const auto run = [&](const std::vector<std::string>& args) {
      const auto result = runLfcam(args, b);
      ASSERT_EQ(result.exitStatus, 0) << args[0] << ": " << result.err;
    };
    run({"synth", "--views", "3", "--size", "16", "-o", (b / "lf.lf.h5").string(), "--disparity",
         (b / "disparity.pfm").string()});
    run({"convert", (b / "lf.lf.h5").string(), "-o", (b / "lenslet.png").string()});
    run({"convert", (b / "lf.lf.h5").string(), "-o", (b / "lenslet.tif").string(), "--16bit"});
    run({"convert", (b / "lf.lf.h5").string(), "-o", (b / "lenslet.jpg").string()});
    run({"convert", (b / "lf.lf.h5").string(), "-o", (b / "hci").string()});
    run({"convert", (b / "lf.lf.h5").string(), "-o", (b / "rc").string(), "--layout", "rowcol"});
    // A simulated raw with its white image and camera.json, and a white image of another size.
    run({"simulate", "pinhole", "-o", (b / "sim").string(), "--size", "64", "--samples", "1", "--no-ground-truth"});
    run({"simulate", "white", "-o", (b / "sim48").string(), "--size", "48", "--samples", "1", "--no-ground-truth"});
  }
  static void TearDownTestSuite() { delete base_; }
  static fs::path base(const std::string& name) { return base_->path() / name; }

  // One bad input: `make` builds it in `folder` and returns the path given to the command.
  struct Case {
    std::string name;
    std::function<fs::path(const fs::path& folder)> make;
    std::string mentioned;  // the message must name this (the bad file); "a|b": a or b
    enum Kind { LightField, Scene, Decode } kind = LightField;
    std::vector<std::string> extra = {};  // more arguments
    std::string memoryLimitEnv = {};      // LFCAM_MEMORY_LIMIT for this run
  };

  void runCases(const std::vector<Case>& cases);

 private:
  static test::TempDir* base_;
};
test::TempDir* BadInputCorpus::base_ = nullptr;
struct BadInputCorpusRaw : BadInputCorpus {
  using BadInputCorpus::base;
};

// Every entry under `folder` (not following links): its type and, for files, its content.
std::map<std::string, std::string> snapshot(const fs::path& folder) {
  std::map<std::string, std::string> entries;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    const auto status = entry.symlink_status();
    std::string what = fs::is_symlink(status)     ? "link " + fs::read_symlink(entry.path()).string()
                       : fs::is_directory(status) ? std::string("folder")
                                                  : "file " + readBytes(entry.path());
    entries[fs::relative(entry.path(), folder).string()] = std::move(what);
  }
  return entries;
}

void BadInputCorpus::runCases(const std::vector<Case>& cases) {
  for (const Case& bad : cases) {
    SCOPED_TRACE(bad.name);
    test::TempDir scratch;
    const fs::path folder = scratch / "case";
    fs::create_directories(folder);
    const fs::path input = bad.make(folder);
    std::vector<std::string> command;
    if (bad.kind == Case::LightField)
      command = {"convert", input.string(), "-o", (folder / "out.lf.h5").string()};
    else if (bad.kind == Case::Scene)
      command = {"simulate", input.string(), "-o", (folder / "simulated").string(), "--size", "64", "--samples", "1"};
    else
      command = {"decode", input.string(), "-o", (folder / "out.lf.h5").string()};
    for (std::string argument : bad.extra) {  // "{folder}/name": a file of the case
      if (argument.rfind("{folder}/", 0) == 0) argument = (folder / argument.substr(9)).string();
      command.push_back(argument);
    }

    const auto before = snapshot(folder);
    if (!bad.memoryLimitEnv.empty()) setenv("LFCAM_MEMORY_LIMIT", bad.memoryLimitEnv.c_str(), 1);
    const auto result = runLfcam(command, scratch.path());
    unsetenv("LFCAM_MEMORY_LIMIT");

    EXPECT_EQ(result.signal, 0);
    EXPECT_TRUE(result.exitStatus == 1 || result.exitStatus == 2) << result.exitStatus << ": " << result.err;
    EXPECT_EQ(result.errLines(), 1) << result.err;
    EXPECT_EQ(result.err.rfind("lfcam: ", 0), 0u) << result.err;
    bool named = false;
    for (std::size_t at = 0; at <= bad.mentioned.size();) {
      const std::size_t bar = std::min(bad.mentioned.find('|', at), bad.mentioned.size());
      named |= result.err.find(bad.mentioned.substr(at, bar - at)) != std::string::npos;
      at = bar + 1;
    }
    EXPECT_TRUE(named) << "expected " << bad.mentioned << " in: " << result.err;
    EXPECT_TRUE(before == snapshot(folder)) << "the case's folder changed (output, temporary or input)";
  }
}

// ---- Helpers that damage files ----

std::string truncated(const fs::path& path, double fraction) {
  const std::string bytes = readBytes(path);
  return bytes.substr(0, std::size_t(double(bytes.size()) * fraction));
}

fs::path withBytes(const fs::path& folder, const std::string& name, const std::string& bytes) {
  writeBytes(folder / name, bytes);
  return folder / name;
}

fs::path copied(const fs::path& from, const fs::path& folder, const std::string& name) {
  fs::copy(from, folder / name, fs::copy_options::recursive);
  return folder / name;
}

std::uint32_t crc32(const std::string& bytes, std::size_t begin, std::size_t end) {
  std::uint32_t crc = 0xffffffffu;
  for (std::size_t i = begin; i < end; ++i) {
    crc ^= std::uint8_t(bytes[i]);
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void putBigEndian(std::string& bytes, std::size_t at, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) bytes[at + std::size_t(i)] = char(value >> (24 - 8 * i));
}

// A PNG whose IHDR claims width x height, with a correct CRC (so only the size is wrong).
std::string pngClaiming(const fs::path& png, std::uint32_t width, std::uint32_t height) {
  std::string bytes = readBytes(png);
  putBigEndian(bytes, 16, width);
  putBigEndian(bytes, 20, height);
  putBigEndian(bytes, 29, crc32(bytes, 12, 29));
  return bytes;
}

// An HDF5 file with a /lightfield dataset of the given shape and type, optionally filled, plus
// string and number attributes on the root.
struct H5Spec {
  std::vector<hsize_t> dims{3, 3, 1, 4, 4};
  hid_t type = H5T_NATIVE_FLOAT;
  bool write = true;
  float value = 0.5f;
  std::map<std::string, std::string> strings{{"lfcam_format", "lfcam-lightfield"}, {"axes", "v,u,c,t,s"}};
  std::map<std::string, double> numbers{{"lfcam_version", 1}};
  std::vector<hsize_t> weightDims{};
  std::map<std::string, std::string> sampleStrings{};  // attributes of /lightfield: encoding
  std::map<std::string, double> sampleNumbers{};       // and scale
};

void writeAttributes(hid_t object, const std::map<std::string, std::string>& strings,
                     const std::map<std::string, double>& numbers) {
  for (const auto& [name, value] : strings) {
    hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, value.size() + 1);
    hid_t space = H5Screate(H5S_SCALAR);
    hid_t attribute = H5Acreate2(object, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(attribute, type, value.c_str());
    H5Aclose(attribute), H5Sclose(space), H5Tclose(type);
  }
  for (const auto& [name, value] : numbers) {
    hid_t space = H5Screate(H5S_SCALAR);
    hid_t attribute = H5Acreate2(object, name.c_str(), H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(attribute, H5T_NATIVE_DOUBLE, &value);
    H5Aclose(attribute), H5Sclose(space);
  }
}

fs::path writeH5(const fs::path& path, const H5Spec& spec) {
  hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  writeAttributes(file, spec.strings, spec.numbers);
  const auto dataset = [&](const char* name, const std::vector<hsize_t>& dims) {
    const std::vector<hsize_t> unlimited(dims.size(), H5S_UNLIMITED);  // chunks may exceed a dimension
    hid_t space = H5Screate_simple(int(dims.size()), dims.data(), unlimited.data());
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    std::vector<hsize_t> chunk(dims.size(), 1);
    chunk.back() = std::min<hsize_t>(dims.back(), 64);
    H5Pset_chunk(dcpl, int(dims.size()), chunk.data());
    hid_t data = H5Dcreate2(file, name, spec.type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    if (spec.write) {
      hsize_t count = 1;
      for (hsize_t d : dims) count *= d;
      std::vector<float> values(count, spec.value);
      H5Dwrite(data, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    }
    if (std::string(name) == "lightfield") writeAttributes(data, spec.sampleStrings, spec.sampleNumbers);
    H5Dclose(data), H5Pclose(dcpl), H5Sclose(space);
  };
  dataset("lightfield", spec.dims);
  if (!spec.weightDims.empty()) dataset("weight", spec.weightDims);
  H5Fclose(file);
  return path;
}

// A copy of lfcam's own file `from` whose chunk of view (0, 0) is replaced by `stored` bytes.
fs::path withChunk(const fs::path& from, const fs::path& folder, const std::string& stored) {
  const fs::path path = folder / "a.lf.h5";
  fs::copy_file(from, path);
  hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  hid_t data = H5Dopen2(file, "lightfield", H5P_DEFAULT);
  const hsize_t origin[5] = {};
  H5Dwrite_chunk(data, H5P_DEFAULT, 0, origin, stored.size(), stored.data());
  H5Dclose(data), H5Fclose(file);
  return path;
}

// A float image (TIFF or EXR by name) holding a lenslet image with one bad value.
fs::path floatLenslet(const fs::path& path, float bad) {
  Image image(12, 12, 1);
  for (std::size_t i = 0; i < image.planeSize(); ++i) image.plane(0)[i] = 0.25f;
  image.at(5, 7, 0) = bad;
  EXPECT_TRUE(writeImage(path, image, {.sampleType = SampleType::Float32}).ok());
  return path;
}

fs::path pfmWith(const fs::path& path, const std::string& header, std::size_t floats, float value) {
  std::string bytes = header;
  for (std::size_t i = 0; i < floats; ++i) bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
  writeBytes(path, bytes);
  return path;
}

// A scene whose only plane shows `image` (relative to the scene file).
fs::path sceneShowing(const fs::path& folder, const std::string& image) {
  return withBytes(
      folder, "scene.json",
      R"({"planes": [{"centre_mm": [0, 0, 500], "texture": {"type": "image", "file": ")" + image + R"("}}]})");
}

fs::path scene(const fs::path& folder, const std::string& json) { return withBytes(folder, "scene.json", json); }

// ---- The corpus ----

TEST_F(BadInputCorpus, Hdf5) {
  runCases({
      {"h5 truncated to half", [](auto f) { return withBytes(f, "a.lf.h5", truncated(base("lf.lf.h5"), 0.5)); },
       "a.lf.h5"},
      {"h5 truncated to 100 bytes",
       [](auto f) { return withBytes(f, "a.lf.h5", readBytes(base("lf.lf.h5")).substr(0, 100)); }, "a.lf.h5"},
      {"h5 empty file", [](auto f) { return withBytes(f, "a.lf.h5", ""); }, "a.lf.h5"},
      {"h5 wrong magic",
       [](auto f) {
         std::string bytes = readBytes(base("lf.lf.h5"));
         bytes[1] = 'X';
         return withBytes(f, "a.lf.h5", bytes);
       },
       "a.lf.h5"},
      {"h5 absurd dimensions, nothing written",
       [](auto f) {
         return writeH5(f / "a.lf.h5", {.dims = {64, 64, 3, 4096, 4096}, .write = false});
       },
       "a.lf.h5"},
      {"h5 dimensions beyond the memory limit",
       [](auto f) {
         return writeH5(f / "a.lf.h5", {.dims = {3, 3, 1, 64, 64}});
       },
       "a.lf.h5",
       Case::LightField,
       {"--memory-limit", "64K"}},
      {"h5 too large for LFCAM_MEMORY_LIMIT",
       [](auto f) { return copied(base("lf.lf.h5"), f, "a.lf.h5"); },
       "a.lf.h5",
       Case::LightField,
       {},
       "2K"},
      {"h5 zero-sized dimension",
       [](auto f) {
         return writeH5(f / "a.lf.h5", {.dims = {3, 3, 1, 0, 4}, .write = false});
       },
       "a.lf.h5"},
      {"h5 wrong rank",
       [](auto f) {
         return writeH5(f / "a.lf.h5", {.dims = {3, 3, 16}});
       },
       "a.lf.h5"},
      {"h5 integer samples", [](auto f) { return writeH5(f / "a.lf.h5", {.type = H5T_NATIVE_INT, .write = false}); },
       "a.lf.h5"},
      {"h5 another format tag",
       [](auto f) {
         return writeH5(f / "a.lf.h5", {.strings = {{"lfcam_format", "something-else"}, {"axes", "v,u,c,t,s"}}});
       },
       "a.lf.h5"},
      {"h5 newer version",
       [](auto f) {
         return writeH5(f / "a.lf.h5", {.numbers = {{"lfcam_version", 99}}});
       },
       "a.lf.h5"},
      {"h5 other axes",
       [](auto f) {
         return writeH5(f / "a.lf.h5", {.strings = {{"lfcam_format", "lfcam-lightfield"}, {"axes", "s,t,u,v,c"}}});
       },
       "a.lf.h5"},
      {"h5 weight of other dimensions",
       [](auto f) {
         return writeH5(f / "a.lf.h5", {.weightDims = {3, 3, 5, 4}});
       },
       "a.lf.h5"},
      {"h5 incomplete optics",
       [](auto f) {
         return writeH5(f / "a.lf.h5", {.numbers = {{"lfcam_version", 1}, {"lens_step_mm", 0.5}}});
       },
       "a.lf.h5"},
      {"h5 NaN samples",
       [](auto f) { return writeH5(f / "a.lf.h5", {.value = std::numeric_limits<float>::quiet_NaN()}); }, "a.lf.h5"},
      {"h5 infinite samples",
       [](auto f) { return writeH5(f / "a.lf.h5", {.value = std::numeric_limits<float>::infinity()}); }, "a.lf.h5"},
      {"h5 negative infinity, with a weight",
       [](auto f) {
         return writeH5(f / "a.lf.h5", {.value = -std::numeric_limits<float>::infinity(), .weightDims = {3, 3, 4, 4}});
       },
       "a.lf.h5"},
      {"h5 8-bit codes without an encoding", [](auto f) { return writeH5(f / "a.lf.h5", {.type = H5T_STD_U8LE}); },
       "a.lf.h5"},
      {"h5 linear codes with a NaN scale",
       [](auto f) {
         return writeH5(f / "a.lf.h5", {.type = H5T_STD_U16LE,
                                        .sampleStrings = {{"encoding", "linear"}},
                                        .sampleNumbers = {{"scale", std::numeric_limits<double>::quiet_NaN()}}});
       },
       "a.lf.h5"},
      {"h5 sRGB said of floats",
       [](auto f) {
         return writeH5(f / "a.lf.h5", {.sampleStrings = {{"encoding", "srgb8"}}});
       },
       "a.lf.h5"},
      {"h5 chunk shorter than a view", [](auto f) { return withChunk(base("lf.lf.h5"), f, "\x78\x01\x63\x00"); },
       "a.lf.h5"},
      {"h5 chunk that is no deflate stream",
       [](auto f) { return withChunk(base("lf.lf.h5"), f, std::string(5000, 'x')); }, "a.lf.h5"},
      {"a folder named like an h5 file",
       [](auto f) {
         fs::create_directories(f / "a.lf.h5");
         return f / "a.lf.h5";
       },
       "a.lf.h5"},
  });
}

TEST_F(BadInputCorpus, LensletImages) {
  runCases({
      {"png truncated", [](auto f) { return withBytes(f, "l.png", truncated(base("lenslet.png"), 0.6)); }, "l.png"},
      {"png empty", [](auto f) { return withBytes(f, "l.png", ""); }, "l.png"},
      {"png wrong magic",
       [](auto f) {
         std::string bytes = readBytes(base("lenslet.png"));
         bytes[1] = 'Q';
         return withBytes(f, "l.png", bytes);
       },
       "l.png"},
      {"png claims 100000 x 100000 pixels",
       [](auto f) { return withBytes(f, "l.png", pngClaiming(base("lenslet.png"), 100000, 100000)); }, "l.png"},
      {"png claims 2^31-1 x 2^31-1 pixels",
       [](auto f) { return withBytes(f, "l.png", pngClaiming(base("lenslet.png"), 0x7fffffff, 0x7fffffff)); }, "l.png"},
      {"png of zero width", [](auto f) { return withBytes(f, "l.png", pngClaiming(base("lenslet.png"), 0, 48)); },
       "l.png"},
      {"png with a bad header CRC",
       [](auto f) {
         std::string bytes = readBytes(base("lenslet.png"));
         bytes[30] = char(bytes[30] ^ 0x55);
         return withBytes(f, "l.png", bytes);
       },
       "l.png"},
      {"text named .png", [](auto f) { return withBytes(f, "l.png", "hello, I am not a picture\n"); }, "l.png"},
      {"lenslet views that do not divide the image",
       [](auto f) {
         EXPECT_TRUE(writeImage(f / "l.png", Image(12, 12, 3)).ok());  // no description: the option decides
         return f / "l.png";
       },
       "l.png",
       Case::LightField,
       {"--lenslet-views", "5"}},
      {"tiff truncated", [](auto f) { return withBytes(f, "l.tif", truncated(base("lenslet.tif"), 0.5)); }, "l.tif"},
      {"tiff wrong magic",
       [](auto f) {
         std::string bytes = readBytes(base("lenslet.tif"));
         bytes[2] = 0x2b;
         bytes[3] = 0x2b;
         return withBytes(f, "l.tif", bytes);
       },
       "l.tif"},
      {"jpeg truncated", [](auto f) { return withBytes(f, "l.jpg", truncated(base("lenslet.jpg"), 0.3)); }, "l.jpg"},
      {"float tiff with NaN",
       [](auto f) { return floatLenslet(f / "l.tif", std::nanf("")); },
       "l.tif",
       Case::LightField,
       {"--lenslet-views", "3"}},
      {"exr with infinity",
       [](auto f) { return floatLenslet(f / "l.exr", std::numeric_limits<float>::infinity()); },
       "l.exr",
       Case::LightField,
       {"--lenslet-views", "3"}},
      {"a folder named like an image",
       [](auto f) {
         fs::create_directories(f / "l.png");
         return f / "l.png";
       },
       "l.png"},
  });
}

TEST_F(BadInputCorpus, ViewFolders) {
  runCases({
      {"hci view emptied",
       [](auto f) {
         auto folder = copied(base("hci"), f, "hci");
         writeBytes(folder / "input_Cam003.png", "");
         return folder;
       },
       "input_Cam003.png"},
      {"hci view is a folder",
       [](auto f) {
         auto folder = copied(base("hci"), f, "hci");
         fs::remove(folder / "input_Cam003.png");
         fs::create_directories(folder / "input_Cam003.png");
         return folder;
       },
       "input_Cam003.png"},
      {"hci view links to /dev/zero",
       [](auto f) {
         auto folder = copied(base("hci"), f, "hci");
         fs::remove(folder / "input_Cam002.png");
         fs::create_symlink("/dev/zero", folder / "input_Cam002.png");
         return folder;
       },
       "input_Cam002.png"},
      {"hci view of another channel count",
       [](auto f) {
         auto folder = copied(base("hci"), f, "hci");
         Image grey(16, 16, 1);
         EXPECT_TRUE(writeImage(folder / "input_Cam006.png", grey).ok());
         return folder;
       },
       "input_Cam006.png"},
      {"hci view claims huge size",
       [](auto f) {
         auto folder = copied(base("hci"), f, "hci");
         writeBytes(folder / "input_Cam001.png", pngClaiming(folder / "input_Cam001.png", 60000, 60000));
         return folder;
       },
       "input_Cam001.png"},
      {"hci eight views, no square",
       [](auto f) {
         auto folder = copied(base("hci"), f, "hci");
         fs::remove(folder / "input_Cam008.png");
         fs::remove(folder / "parameters.cfg");
         return folder;
       },
       "hci"},
      {"hci parameters.cfg with a word for a number",
       [](auto f) {
         auto folder = copied(base("hci"), f, "hci");
         writeBytes(folder / "parameters.cfg", "[extrinsics]\nnum_cams_x = three\nnum_cams_y = 3\n");
         return folder;
       },
       "parameters.cfg"},
      {"hci parameters.cfg grid that does not match the views",
       [](auto f) {
         auto folder = copied(base("hci"), f, "hci");
         writeBytes(folder / "parameters.cfg", "[extrinsics]\nnum_cams_x = 4\nnum_cams_y = 4\n");
         return folder;
       },
       "hci"},
      {"hci parameters.cfg absurd grid",
       [](auto f) {
         auto folder = copied(base("hci"), f, "hci");
         writeBytes(folder / "parameters.cfg", "[extrinsics]\nnum_cams_x = 2000000000\nnum_cams_y = 2000000000\n");
         return folder;
       },
       "hci"},
      {"hci parameters.cfg is a folder",
       [](auto f) {
         auto folder = copied(base("hci"), f, "hci");
         fs::remove(folder / "parameters.cfg");
         fs::create_directories(folder / "parameters.cfg");
         return folder;
       },
       "parameters.cfg"},
      {"row/column view missing",
       [](auto f) {
         auto folder = copied(base("rc"), f, "rc");
         for (const auto& entry : fs::directory_iterator(folder))
           if (entry.path().filename().string().find("_02_02") != std::string::npos) fs::remove(entry.path());
         return folder;
       },
       "rc"},
      {"row/column view of another size",
       [](auto f) {
         auto folder = copied(base("rc"), f, "rc");
         for (const auto& entry : fs::directory_iterator(folder))
           if (entry.path().filename().string().find("_01_03") != std::string::npos) {
             EXPECT_TRUE(writeImage(entry.path(), Image(20, 16, 3)).ok());
           }
         return folder;
       },
       "_01_03"},
      {"row/column view truncated",
       [](auto f) {
         auto folder = copied(base("rc"), f, "rc");
         for (const auto& entry : fs::directory_iterator(folder))
           if (entry.path().filename().string().find("_03_01") != std::string::npos)
             writeBytes(entry.path(), truncated(entry.path(), 0.5));
         return folder;
       },
       "_03_01"},
      {"both layouts in one folder",
       [](auto f) {
         auto folder = copied(base("hci"), f, "both");
         for (const auto& entry : fs::directory_iterator(base("rc"))) fs::copy(entry.path(), folder);
         return folder;
       },
       "both"},
      {"views/ subfolder with a corrupt view",
       [](auto f) {
         fs::create_directories(f / "set");
         auto folder = copied(base("hci"), f / "set", "views");
         writeBytes(folder / "input_Cam004.png", "PNG? no.");
         return f / "set";
       },
       "input_Cam004.png"},
      {"a file of zeros named like a folder", [](auto f) { return withBytes(f, "views", std::string(4096, '\0')); },
       "views"},
  });
}

TEST_F(BadInputCorpus, SceneFiles) {
  runCases({
      {"scene truncated", [](auto f) { return scene(f, R"({"planes": [{"centre_mm": [0, 0, 5)"); }, "scene.json",
       Case::Scene},
      {"scene empty", [](auto f) { return scene(f, ""); }, "scene.json", Case::Scene},
      {"scene binary", [](auto f) { return scene(f, std::string("\x89PNG\r\n\x1a\n\0\0\0", 11)); }, "scene.json",
       Case::Scene},
      {"scene is an array", [](auto f) { return scene(f, "[1, 2, 3]"); }, "scene.json", Case::Scene},
      {"planes is a string", [](auto f) { return scene(f, R"({"planes": "many"})"); }, "scene.json", Case::Scene},
      {"centre of two numbers", [](auto f) { return scene(f, R"({"planes": [{"centre_mm": [0, 500]}]})"); },
       "scene.json", Case::Scene},
      {"centre given as text", [](auto f) { return scene(f, R"({"planes": [{"centre_mm": ["0", "0", "500"]}]})"); },
       "scene.json", Case::Scene},
      {"unknown texture",
       [](auto f) { return scene(f, R"({"planes": [{"centre_mm": [0, 0, 500], "texture": {"type": "plaid"}}]})"); },
       "scene.json", Case::Scene},
      {"overflowing number",
       [](auto f) { return scene(f, R"({"camera": {"main_lens": {"focal_length_mm": 1e999}}})"); }, "scene.json",
       Case::Scene},
      {"absurd sensor",
       [](auto f) { return scene(f, R"({"camera": {"sensor": {"width": 1000000000000, "height": 3}}})"); },
       "scene.json", Case::Scene},
      {"sensor beyond the memory limit",
       [](auto f) { return scene(f, R"({"camera": {"sensor": {"width": 30000, "height": 30000}}})"); },
       "scene.json",
       Case::Scene,
       {"--memory-limit", "1G"}},
      {"negative f-number", [](auto f) { return scene(f, R"({"camera": {"main_lens": {"f_number": -2}}})"); },
       "scene.json", Case::Scene},
      {"nested ten thousand deep", [](auto f) { return scene(f, std::string(10000, '[') + std::string(10000, ']')); },
       "scene.json", Case::Scene},
      {"scene is a folder",
       [](auto f) {
         fs::create_directories(f / "scene.json");
         return f / "scene.json";
       },
       "scene.json", Case::Scene},
      {"texture image missing", [](auto f) { return sceneShowing(f, "missing.png"); }, "missing.png", Case::Scene},
      {"texture png truncated",
       [](auto f) {
         withBytes(f, "t.png", truncated(base("lenslet.png"), 0.4));
         return sceneShowing(f, "t.png");
       },
       "t.png", Case::Scene},
      {"texture pfm truncated",
       [](auto f) {
         withBytes(f, "t.pfm", truncated(base("disparity.pfm"), 0.7));
         return sceneShowing(f, "t.pfm");
       },
       "t.pfm", Case::Scene},
      {"texture pfm of absurd size",
       [](auto f) {
         pfmWith(f / "t.pfm", "Pf\n100000 100000\n-1.0\n", 16, 0.5f);
         return sceneShowing(f, "t.pfm");
       },
       "t.pfm", Case::Scene},
      {"texture pfm of zero size",
       [](auto f) {
         pfmWith(f / "t.pfm", "Pf\n0 0\n-1.0\n", 0, 0.5f);
         return sceneShowing(f, "t.pfm");
       },
       "t.pfm", Case::Scene},
      {"texture pfm with NaN",
       [](auto f) {
         pfmWith(f / "t.pfm", "Pf\n4 4\n-1.0\n", 16, std::nanf(""));
         return sceneShowing(f, "t.pfm");
       },
       "t.pfm", Case::Scene},
      {"texture pfm with a NaN scale",
       [](auto f) {
         pfmWith(f / "t.pfm", "PF\n4 4\nnan\n", 48, 0.5f);
         return sceneShowing(f, "t.pfm");
       },
       "t.pfm", Case::Scene},
      {"texture pfm wrong magic",
       [](auto f) {
         pfmWith(f / "t.pfm", "P6\n4 4\n-1.0\n", 16, 0.5f);
         return sceneShowing(f, "t.pfm");
       },
       "t.pfm", Case::Scene},
      {"texture is /dev/zero", [](auto f) { return sceneShowing(f, "/dev/zero"); }, "/dev/zero", Case::Scene},
  });
}

// Raw decoding: a raw with the camera.json lfcam simulate wrote beside it, damaged one way each.
fs::path simulatedRaw(const fs::path& folder) {
  fs::copy_file(BadInputCorpusRaw::base("sim/raw.png"), folder / "raw.png");
  fs::copy_file(BadInputCorpusRaw::base("sim/camera.json"), folder / "camera.json");
  return folder / "raw.png";
}

TEST_F(BadInputCorpus, RawDecoding) {
  runCases({
      {"white image of another size than the raw",
       [](auto f) {
         fs::copy_file(base("sim48/white.png"), f / "other.png");
         return simulatedRaw(f);
       },
       "other.png",
       Case::Decode,
       {"--white", "{folder}/other.png"}},
      {"white image truncated",
       [](auto f) {
         withBytes(f, "white.png", truncated(base("sim/white.png"), 0.5));
         return simulatedRaw(f);
       },
       "white.png",
       Case::Decode,
       {"--white", "{folder}/white.png"}},
      {"white image is a folder",
       [](auto f) {
         fs::create_directories(f / "white.png");
         return simulatedRaw(f);
       },
       "white.png",
       Case::Decode,
       {"--white", "{folder}/white.png"}},
      {"raw truncated",
       [](auto f) {
         simulatedRaw(f);
         return withBytes(f, "raw.png", truncated(base("sim/raw.png"), 0.5));
       },
       "raw.png", Case::Decode},
      {"raw beside a camera.json of the wrong type",
       [](auto f) {
         simulatedRaw(f);
         writeBytes(f / "camera.json", R"({"sensor": "big"})");
         return f / "raw.png";
       },
       "camera.json|raw.png", Case::Decode},
      {"grid.json of the wrong types",
       [](auto f) {
         withBytes(f, "grid.json", R"({"format": 3, "pitch_x_px": "wide"})");
         return simulatedRaw(f);
       },
       "grid.json",
       Case::Decode,
       {"--grid", "{folder}/grid.json"}},
      {"grid.json with an absurd lattice",
       [](auto f) {
         withBytes(f, "grid.json",
                   R"({"format": "lfcam-lenslet-grid", "version": 1, "packing": "square", "pitch_x_px": 1e-300,)"
                   R"( "pitch_y_px": 1e-300, "rotation_deg": 0, "origin_px": [0, 0], "columns": 2000000000,)"
                   R"( "rows": 2000000000, "hex_parity": 0})");
         return simulatedRaw(f);
       },
       "grid.json",
       Case::Decode,
       {"--grid", "{folder}/grid.json"}},
      {"lytro container truncated",
       [](auto f) { return withBytes(f, "raw.lfp", std::string("\x89LFP\r\n\x1a\n\0\0\0\1\0\0\0\0\x89LFM", 20)); },
       "raw.lfp", Case::Decode},
  });
}

TEST_F(BadInputCorpus, MemoryLimitSettings) {
  runCases({
      {"memory limit of zero",
       [](auto f) { return copied(base("lf.lf.h5"), f, "a.lf.h5"); },
       "--memory-limit",
       Case::LightField,
       {"--memory-limit", "0"}},
      {"memory limit that is not a size",
       [](auto f) { return copied(base("lf.lf.h5"), f, "a.lf.h5"); },
       "--memory-limit",
       Case::LightField,
       {"--memory-limit", "lots"}},
      {"LFCAM_MEMORY_LIMIT that is not a size",
       [](auto f) { return copied(base("lf.lf.h5"), f, "a.lf.h5"); },
       "LFCAM_MEMORY_LIMIT",
       Case::LightField,
       {},
       "12 parsecs"},
  });
}

// The message for a too-large input says what it needs and the limit.
TEST_F(BadInputCorpus, MemoryMessageGivesNeedAndLimit) {
  test::TempDir dir;
  const auto result = runLfcam({"--memory-limit", "10K", "info", base("lf.lf.h5").string()}, dir.path());
  EXPECT_EQ(result.exitStatus, 1) << result.err;
  EXPECT_NE(result.err.find("needs 27.0 KiB of memory"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("limit of 10.0 KiB"), std::string::npos) << result.err;
  const auto fine = runLfcam({"--memory-limit", "1M", "info", base("lf.lf.h5").string()}, dir.path());
  EXPECT_EQ(fine.exitStatus, 0) << fine.err;
}

}  // namespace
}  // namespace lfcam
