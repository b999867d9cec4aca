#include "lfcam/io/light_field_io.hpp"

#include "lfcam/synth/layered_planes.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>  // to write HDF5 files of other layouts

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "lfcam/io/image_io.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

enum class Quantise { None, Srgb8, Linear16 };

// Random samples in [0, 1], snapped to what the output's bit depth holds exactly.
LightField randomLightField(const LightFieldShape& shape, unsigned seed, Quantise quantise = Quantise::None) {
  LightField lf(shape);
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (float& value : lf.samples()) {
    value = uniform(random);
    if (quantise == Quantise::Srgb8) value = linearFromSrgb(std::round(srgbFromLinear(value) * 255.0f) / 255.0f);
    if (quantise == Quantise::Linear16) value = float(std::round(value * 65535.0) / 65535.0);
  }
  return lf;
}

float maxDifference(const LightField& a, const LightField& b) {
  EXPECT_EQ(a.shape(), b.shape());
  if (a.shape() != b.shape()) return INFINITY;
  float worst = 0;
  for (std::size_t i = 0; i < a.samples().size(); ++i)
    worst = std::max(worst, std::abs(a.samples()[i] - b.samples()[i]));
  return worst;
}

std::set<std::string> namesIn(const fs::path& folder) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.insert(entry.path().filename().string());
  return names;
}

// The read fails with a one-line message that contains `mentioned`.
template <class T>
void expectErrorMentioning(const Result<T>& result, const std::string& mentioned) {
  ASSERT_FALSE(result.ok()) << "expected an error mentioning " << mentioned;
  EXPECT_NE(result.error().message.find(mentioned), std::string::npos) << result.error().message;
  EXPECT_EQ(result.error().message.find('\n'), std::string::npos) << result.error().message;
}

// Progress fractions seen by a callback.
struct ProgressLog {
  std::vector<double> fractions;
  ProgressCallback callback() {
    return [this](double fraction) { fractions.push_back(fraction); };
  }
  void expectComplete() const {
    ASSERT_FALSE(fractions.empty());
    for (std::size_t i = 1; i < fractions.size(); ++i) EXPECT_GE(fractions[i], fractions[i - 1]);
    EXPECT_GE(fractions.front(), 0.0);
    EXPECT_DOUBLE_EQ(fractions.back(), 1.0);
  }
};

const LightFieldShape kSmall{.nu = 3, .nv = 2, .ns = 7, .nt = 5, .channels = 3};

TEST(LightFieldIo, FormatNames) {
  EXPECT_STREQ(formatName(LightFieldFormat::Hdf5), "lf.h5");
  EXPECT_STREQ(formatName(LightFieldFormat::HciFolder), "hci-folder");
  EXPECT_STREQ(formatName(LightFieldFormat::RowColumnFolder), "rowcol-folder");
  EXPECT_STREQ(formatName(LightFieldFormat::LensletImage), "lenslet-image");
}

// ---- HDF5 ----

TEST(LightFieldIoHdf5, RoundTripIsExactWithWeightAndMetadata) {
  test::TempDir dir;
  LightField lf = randomLightField(kSmall, 1);
  lf.samples()[0] = -7.5f;  // floats: anything goes
  lf.samples()[1] = 1e9f;
  lf.enableWeight(0.25f);
  lf.weights()[3] = 1.0f;
  lf.metadata.optics =
      Optics{.lensStepMm = 0.5, .spatialStepMm = 0.0125, .lensToMicrolensMm = 80.0, .focalLengthMm = 75.0};
  lf.metadata.disparityMin = -1.25;
  lf.metadata.disparityMax = 2.5;
  lf.metadata.source = "synthetic: layered planes, ünïcode";
  const fs::path path = dir / "a.lf.h5";
  ProgressLog writeLog, readLog;
  ASSERT_TRUE(writeLightField(path, lf, {}, writeLog.callback()));
  writeLog.expectComplete();

  auto info = probeLightField(path);
  ASSERT_TRUE(info) << info.error().message;
  EXPECT_EQ(info->format, LightFieldFormat::Hdf5);
  EXPECT_EQ(info->shape, kSmall);
  EXPECT_TRUE(info->hasWeight);
  EXPECT_EQ(info->metadata.source, lf.metadata.source);

  auto read = readLightField(path, {}, readLog.callback());
  ASSERT_TRUE(read) << read.error().message;
  readLog.expectComplete();
  EXPECT_EQ(maxDifference(*read, lf), 0.0f);
  ASSERT_TRUE(read->hasWeight());
  EXPECT_TRUE(std::equal(lf.weights().begin(), lf.weights().end(), read->weights().begin()));
  ASSERT_TRUE(read->metadata.optics);
  EXPECT_EQ(read->metadata.optics->lensStepMm, 0.5);
  EXPECT_EQ(read->metadata.optics->spatialStepMm, 0.0125);
  EXPECT_EQ(read->metadata.optics->lensToMicrolensMm, 80.0);
  EXPECT_EQ(read->metadata.optics->focalLengthMm, 75.0);
  EXPECT_EQ(read->metadata.disparityMin, -1.25);
  EXPECT_EQ(read->metadata.disparityMax, 2.5);
  EXPECT_EQ(read->metadata.source, lf.metadata.source);
}

TEST(LightFieldIoHdf5, WithoutWeightOrMetadata) {
  test::TempDir dir;
  const LightField lf = randomLightField({.nu = 1, .nv = 4, .ns = 3, .nt = 9, .channels = 1}, 2);
  ASSERT_TRUE(writeLightField(dir / "b.h5", lf));
  auto read = readLightField(dir / "b.h5");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(maxDifference(*read, lf), 0.0f);
  EXPECT_FALSE(read->hasWeight());
  EXPECT_FALSE(read->metadata.optics);
  EXPECT_FALSE(read->metadata.disparityMin);
}

// A fixed-length string attribute of an HDF5 object, as h5py or MATLAB would read it.
std::string readStringAttribute(hid_t object, const char* name) {
  if (H5Aexists(object, name) <= 0) return "(none)";
  hid_t attribute = H5Aopen(object, name, H5P_DEFAULT);
  hid_t type = H5Aget_type(attribute);
  std::string text(H5Tget_size(type), '\0');
  H5Aread(attribute, type, text.data());
  H5Tclose(type), H5Aclose(attribute);
  return text.substr(0, text.find('\0'));
}

double readScaleAttribute(hid_t object) {
  double scale = 0;
  hid_t attribute = H5Aopen(object, "scale", H5P_DEFAULT);
  H5Aread(attribute, H5T_NATIVE_DOUBLE, &scale);
  H5Aclose(attribute);
  return scale;
}

// The layout promised in docs/formats.md, checked with the HDF5 API as h5py or MATLAB would see it.
TEST(LightFieldIoHdf5, FileLayoutIsTheDocumentedOne) {
  test::TempDir dir;
  LightField lf = randomLightField(kSmall, 3);
  lf.enableWeight();
  const fs::path path = dir / "layout.lf.h5";
  ASSERT_TRUE(writeLightField(path, lf));
  EXPECT_EQ(test::readBytes(path).substr(0, 8), "\x89HDF\r\n\x1a\n");

  hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  hid_t data = H5Dopen2(file, "/lightfield", H5P_DEFAULT);
  ASSERT_GE(data, 0);
  hid_t type = H5Dget_type(data);
  EXPECT_TRUE(H5Tequal(type, H5T_IEEE_F32LE) > 0);
  hid_t space = H5Dget_space(data);
  hsize_t dims[5] = {};
  ASSERT_EQ(H5Sget_simple_extent_dims(space, dims, nullptr), 5);
  EXPECT_EQ(std::vector<hsize_t>(dims, dims + 5), (std::vector<hsize_t>{2, 3, 3, 5, 7}));
  hid_t dcpl = H5Dget_create_plist(data);
  hsize_t chunk[5] = {};
  ASSERT_EQ(H5Pget_chunk(dcpl, 5, chunk), 5);
  EXPECT_EQ(std::vector<hsize_t>(chunk, chunk + 5), (std::vector<hsize_t>{1, 1, 3, 5, 7}));
  std::set<H5Z_filter_t> filters;
  for (int i = 0; i < H5Pget_nfilters(dcpl); ++i)
    filters.insert(H5Pget_filter2(dcpl, unsigned(i), nullptr, nullptr, nullptr, 0, nullptr, nullptr));
  EXPECT_TRUE(filters.count(H5Z_FILTER_SHUFFLE));
  EXPECT_TRUE(filters.count(H5Z_FILTER_DEFLATE));
  EXPECT_EQ(readStringAttribute(data, "encoding"), "float");
  // Sample (u=2, v=1, s=6, t=4, c=1) sits at [v][u][c][t][s].
  std::vector<float> all(lf.samples().size());
  ASSERT_GE(H5Dread(data, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, all.data()), 0);
  EXPECT_EQ(all[(((1 * 3 + 2) * 3 + 1) * 5 + 4) * 7 + 6], lf.at(2, 1, 6, 4, 1));
  H5Pclose(dcpl), H5Sclose(space), H5Tclose(type), H5Dclose(data);

  hid_t weight = H5Dopen2(file, "/weight", H5P_DEFAULT);
  ASSERT_GE(weight, 0);
  hid_t weightSpace = H5Dget_space(weight);
  hsize_t weightDims[4] = {};
  ASSERT_EQ(H5Sget_simple_extent_dims(weightSpace, weightDims, nullptr), 4);
  EXPECT_EQ(std::vector<hsize_t>(weightDims, weightDims + 4), (std::vector<hsize_t>{2, 3, 5, 7}));
  // Weights of 1 everywhere: 8-bit codes 255 with a scale of 1/255.
  hid_t weightType = H5Dget_type(weight);
  EXPECT_TRUE(H5Tequal(weightType, H5T_STD_U8LE) > 0);
  EXPECT_EQ(readStringAttribute(weight, "encoding"), "linear");
  EXPECT_EQ(readScaleAttribute(weight), 1.0 / 255.0);
  H5Tclose(weightType), H5Sclose(weightSpace), H5Dclose(weight);

  for (const char* name : {"lfcam_format", "lfcam_version", "axes", "source"})
    EXPECT_GT(H5Aexists(file, name), 0) << name;
  for (const char* name : {"lfcam_format", "axes", "source"}) {  // fixed-length: see the reader
    hid_t attribute = H5Aopen(file, name, H5P_DEFAULT);
    hid_t stringType = H5Aget_type(attribute);
    EXPECT_EQ(H5Tget_class(stringType), H5T_STRING) << name;
    EXPECT_EQ(H5Tis_variable_str(stringType), 0) << name;
    H5Tclose(stringType), H5Aclose(attribute);
  }
  int version = 0;
  hid_t versionAttribute = H5Aopen(file, "lfcam_version", H5P_DEFAULT);
  H5Aread(versionAttribute, H5T_NATIVE_INT, &version);
  H5Aclose(versionAttribute);
  EXPECT_EQ(version, 2);
  EXPECT_EQ(H5Aexists(file, "lens_step_mm"), 0);  // no optics, no attribute
  H5Fclose(file);
}

// Writes an HDF5 file holding one dataset `name` of `type` and `dims`, as another tool would.
void writeForeignHdf5(const fs::path& path, const char* name, hid_t type, std::vector<hsize_t> dims,
                      const char* formatTag = nullptr, bool variableLengthTag = false) {
  hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  hid_t space = H5Screate_simple(int(dims.size()), dims.data(), nullptr);
  hid_t data = H5Dcreate2(file, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  hsize_t count = 1;
  for (hsize_t dim : dims) count *= dim;
  std::vector<double> values(count, 0.5);
  H5Dwrite(data, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  if (formatTag) {
    hid_t stringType = H5Tcopy(H5T_C_S1);
    H5Tset_size(stringType, variableLengthTag ? H5T_VARIABLE : std::strlen(formatTag) + 1);
    hid_t scalar = H5Screate(H5S_SCALAR);
    hid_t attribute = H5Acreate2(file, "lfcam_format", stringType, scalar, H5P_DEFAULT, H5P_DEFAULT);
    if (variableLengthTag)
      H5Awrite(attribute, stringType, &formatTag);
    else
      H5Awrite(attribute, stringType, formatTag);
    H5Aclose(attribute), H5Sclose(scalar), H5Tclose(stringType);
  }
  H5Dclose(data), H5Sclose(space), H5Fclose(file);
}

TEST(LightFieldIoHdf5, OtherLayoutsAreCleanFormatErrors) {
  test::TempDir dir;
  struct Case {
    const char* file;
    const char* dataset;
    hid_t type;
    std::vector<hsize_t> dims;
    const char* tag;
  };
  const std::vector<Case> cases = {
      {"images.h5", "/images", H5T_NATIVE_FLOAT, {4, 4}, nullptr},
      {"rank4.h5", "/lightfield", H5T_NATIVE_FLOAT, {2, 2, 4, 4}, nullptr},
      {"integers.h5", "/lightfield", H5T_NATIVE_INT, {1, 1, 1, 4, 4}, nullptr},
      {"tagged.h5", "/lightfield", H5T_NATIVE_FLOAT, {1, 1, 1, 4, 4}, "something-else"},
  };
  for (const Case& bad : cases) {
    SCOPED_TRACE(bad.file);
    writeForeignHdf5(dir / bad.file, bad.dataset, bad.type, bad.dims, bad.tag);
    auto format = detectLightFieldFormat(dir / bad.file);
    ASSERT_TRUE(format);
    EXPECT_EQ(*format, LightFieldFormat::Hdf5);
    auto read = readLightField(dir / bad.file);
    expectErrorMentioning(read, bad.file);
    EXPECT_EQ(read.error().code, ErrorCode::Format);
    expectErrorMentioning(probeLightField(dir / bad.file), bad.file);
  }
}

TEST(LightFieldIoHdf5, VariableLengthStringAttributesAreRefusedBeforeLibhdf5ReadsThem) {
  // libhdf5 1.10 overflows the heap on a corrupt one (fuzz/regressions/hdf5_light_field).
  test::TempDir dir;
  writeForeignHdf5(dir / "vlen.h5", "/lightfield", H5T_NATIVE_FLOAT, {1, 1, 1, 4, 4}, "lfcam-lightfield",
                   /*variableLengthTag=*/true);
  auto read = readLightField(dir / "vlen.h5");
  expectErrorMentioning(read, "vlen.h5");
  expectErrorMentioning(read, "variable-length");
  EXPECT_EQ(read.error().code, ErrorCode::Unsupported);
}

TEST(LightFieldIoHdf5, AcceptsAnUntaggedFileOfTheRightLayout) {
  test::TempDir dir;
  // As h5py would write it: float64 [nv, nu, c, nt, ns], no attributes.
  writeForeignHdf5(dir / "h5py.h5", "/lightfield", H5T_IEEE_F64LE, {2, 3, 1, 4, 5});
  auto read = readLightField(dir / "h5py.h5");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->shape(), (LightFieldShape{.nu = 3, .nv = 2, .ns = 5, .nt = 4, .channels = 1}));
  EXPECT_EQ(read->at(2, 1, 4, 3, 0), 0.5f);
}

// The precision rule (io/sample_encoding.hpp): the most compact type that gives every sample back.
// The filters of /lightfield in `path`, in pipeline order.
std::vector<H5Z_filter_t> filtersOf(const fs::path& path) {
  hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t data = H5Dopen2(file, "/lightfield", H5P_DEFAULT);
  hid_t dcpl = H5Dget_create_plist(data);
  std::vector<H5Z_filter_t> filters;
  for (int i = 0; i < H5Pget_nfilters(dcpl); ++i)
    filters.push_back(H5Pget_filter2(dcpl, unsigned(i), nullptr, nullptr, nullptr, 0, nullptr, nullptr));
  H5Pclose(dcpl), H5Dclose(data), H5Fclose(file);
  return filters;
}

// Writes `codes` as an srgb8 /lightfield of shape kSmall through libhdf5, one chunk per view,
// with the filters `filter` sets.
void writeCodes(const fs::path& path, const std::vector<std::uint8_t>& codes, void (*filter)(hid_t dcpl)) {
  const hsize_t dims[5] = {2, 3, 3, 5, 7}, chunk[5] = {1, 1, 3, 5, 7};
  hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(dcpl, 5, chunk);
  filter(dcpl);
  hid_t space = H5Screate_simple(5, dims, nullptr);
  hid_t data = H5Dcreate2(file, "lightfield", H5T_STD_U8LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  H5Dwrite(data, H5T_NATIVE_UINT8, H5S_ALL, H5S_ALL, H5P_DEFAULT, codes.data());
  hid_t stringType = H5Tcopy(H5T_C_S1);
  H5Tset_size(stringType, 5);
  hid_t scalar = H5Screate(H5S_SCALAR);
  hid_t encoding = H5Acreate2(data, "encoding", stringType, scalar, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(encoding, stringType, "srgb8");
  H5Aclose(encoding), H5Sclose(scalar), H5Tclose(stringType);
  H5Dclose(data), H5Sclose(space), H5Pclose(dcpl), H5Fclose(file);
}

TEST(LightFieldIoHdf5, SamplesAreStoredInThePrecisionTheyCameIn) {
  test::TempDir dir;
  const LightFieldShape shape{.nu = 3, .nv = 2, .ns = 40, .nt = 30, .channels = 3};
  LightField half = randomLightField(shape, 7);
  for (float& value : half.samples()) value = std::ldexp(std::round(std::ldexp(value, 10)), -10);  // 10-bit steps
  struct Case {
    const char* file;
    LightField lightField;
    hid_t type;
    const char* encoding;
    double scale;
  };
  Case cases[] = {
      {"srgb8.lf.h5", randomLightField(shape, 5, Quantise::Srgb8), H5T_STD_U8LE, "srgb8", 0},
      {"linear16.lf.h5", randomLightField(shape, 6, Quantise::Linear16), H5T_STD_U16LE, "linear", 1.0 / 65535.0},
      {"half.lf.h5", std::move(half), -1, "float", 0},
      {"float.lf.h5", randomLightField(shape, 8), H5T_IEEE_F32LE, "float", 0},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    ASSERT_TRUE(writeLightField(dir / c.file, c.lightField));
    auto read = readLightField(dir / c.file);
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(maxDifference(*read, c.lightField), 0.0f);
    hid_t file = H5Fopen((dir / c.file).c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t data = H5Dopen2(file, "/lightfield", H5P_DEFAULT);
    hid_t type = H5Dget_type(data);
    if (c.type >= 0) {
      EXPECT_TRUE(H5Tequal(type, c.type) > 0);
    } else {
      EXPECT_EQ(H5Tget_class(type), H5T_FLOAT);
      EXPECT_EQ(H5Tget_size(type), 2u);
    }
    EXPECT_EQ(readStringAttribute(data, "encoding"), c.encoding);
    if (c.scale > 0) {
      EXPECT_EQ(readScaleAttribute(data), c.scale);
    }
    if (std::string(c.encoding) == "srgb8") {  // what h5py gets: the sRGB codes themselves
      std::vector<std::uint8_t> codes(c.lightField.samples().size());
      ASSERT_GE(H5Dread(data, H5T_NATIVE_UINT8, H5S_ALL, H5S_ALL, H5P_DEFAULT, codes.data()), 0);
      EXPECT_EQ(codes[17], std::lround(srgbFromLinear(c.lightField.samples()[17]) * 255.0f));
    } else {  // libhdf5 converts float16 and float32 itself, and 16-bit codes times the scale are the samples
      std::vector<float> values(c.lightField.samples().size());
      ASSERT_GE(H5Dread(data, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
      const double scale = c.scale > 0 ? c.scale : 1.0;
      EXPECT_EQ(float(values[17] * scale), c.lightField.samples()[17]);
    }
    H5Tclose(type), H5Dclose(data), H5Fclose(file);
  }
  // 8-bit sRGB costs a quarter of float32 before compression (which does better on floats of few values).
  EXPECT_LT(fs::file_size(dir / "srgb8.lf.h5") * 2, fs::file_size(dir / "float.lf.h5"));
  // Integer codes through szip, floats through shuffle and deflate: HDF5's built-in filters.
  EXPECT_EQ(filtersOf(dir / "srgb8.lf.h5"), std::vector<H5Z_filter_t>{H5Z_FILTER_SZIP});
  EXPECT_EQ(filtersOf(dir / "linear16.lf.h5"), std::vector<H5Z_filter_t>{H5Z_FILTER_SZIP});
  EXPECT_EQ(filtersOf(dir / "float.lf.h5"), (std::vector<H5Z_filter_t>{H5Z_FILTER_SHUFFLE, H5Z_FILTER_DEFLATE}));
}

// A smooth 8-bit light field, as photographs are: szip codes differences of neighbours, so it
// stores far fewer bytes than samples; noise does not shrink, and its views are stored unfiltered
// (the chunk's filter mask says so, and libhdf5 reads them too). A view smaller than one szip
// block is deflated.
TEST(LightFieldIoHdf5, SzipShrinksSmoothCodesAndStoresNoiseAsItIs) {
  test::TempDir dir;
  const LightFieldShape shape{.nu = 2, .nv = 2, .ns = 64, .nt = 48, .channels = 3};
  LightField smooth(shape);
  for (int v = 0; v < 2; ++v)
    for (int u = 0; u < 2; ++u)
      for (int c = 0; c < 3; ++c)
        for (int t = 0; t < shape.nt; ++t)
          for (int s = 0; s < shape.ns; ++s)
            smooth.at(u, v, s, t, c) = linearFromSrgb(float((40 + s + t + 10 * c + u) % 256) / 255.0f);
  const LightField noise = randomLightField(shape, 12, Quantise::Srgb8);
  const LightField tiny = randomLightField({.nu = 2, .nv = 1, .ns = 4, .nt = 2, .channels = 1}, 13, Quantise::Srgb8);
  for (const auto& [name, lf] : {std::pair<const char*, const LightField*>{"smooth.lf.h5", &smooth},
                                 {"noise.lf.h5", &noise},
                                 {"tiny.lf.h5", &tiny}}) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(writeLightField(dir / name, *lf));
    auto read = readLightField(dir / name);
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(maxDifference(*read, *lf), 0.0f);
  }
  const auto storedBytes = [&](const char* name) {
    hid_t file = H5Fopen((dir / name).c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t data = H5Dopen2(file, "/lightfield", H5P_DEFAULT);
    const hsize_t bytes = H5Dget_storage_size(data);
    H5Dclose(data), H5Fclose(file);
    return bytes;
  };
  const hsize_t codes = smooth.samples().size();
  EXPECT_LT(storedBytes("smooth.lf.h5"), codes / 2);  // steps of one code: about 3 bits a sample
  EXPECT_EQ(storedBytes("noise.lf.h5"), codes);
  EXPECT_EQ(filtersOf(dir / "tiny.lf.h5"), std::vector<H5Z_filter_t>{H5Z_FILTER_DEFLATE});

  hid_t file = H5Fopen((dir / "noise.lf.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t data = H5Dopen2(file, "/lightfield", H5P_DEFAULT);
  const hsize_t offset[5] = {1, 1, 0, 0, 0};
  std::uint32_t mask = 0;
  ASSERT_GE(H5Dget_chunk_info_by_coord(data, offset, &mask, nullptr, nullptr), 0);
  EXPECT_EQ(mask, 1u);  // szip skipped
  std::vector<std::uint8_t> stored(noise.samples().size());
  ASSERT_GE(H5Dread(data, H5T_NATIVE_UINT8, H5S_ALL, H5S_ALL, H5P_DEFAULT, stored.data()), 0);
  EXPECT_EQ(stored.back(), std::lround(srgbFromLinear(noise.samples().back()) * 255.0f));
  H5Dclose(data), H5Fclose(file);
}

// 8-bit codes as lfcam wrote them before szip (shuffle-free deflate, the same encoding attribute)
// still read, through lfcam's own inflation.
TEST(LightFieldIoHdf5, DeflatedCodesOfEarlierFilesStillRead) {
  test::TempDir dir;
  const LightField lf = randomLightField(kSmall, 14, Quantise::Srgb8);
  std::vector<std::uint8_t> codes(lf.samples().size());
  for (std::size_t i = 0; i < codes.size(); ++i)
    codes[i] = std::uint8_t(std::lround(srgbFromLinear(lf.samples()[i]) * 255.0f));
  const fs::path path = dir / "deflated.lf.h5";
  writeCodes(path, codes, [](hid_t dcpl) { H5Pset_deflate(dcpl, 1); });
  EXPECT_EQ(filtersOf(path), std::vector<H5Z_filter_t>{H5Z_FILTER_DEFLATE});
  auto read = readLightField(path);
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(maxDifference(*read, lf), 0.0f);
}

// szip parameters libaec cannot take (blocks of 4 pixels: libhdf5 accepts them, libaec does not)
// are one Format error before anything decodes with them.
TEST(LightFieldIoHdf5, SzipParametersOutOfRangeAreAFormatError) {
  test::TempDir dir;
  const fs::path path = dir / "blocks4.lf.h5";
  writeCodes(path, std::vector<std::uint8_t>(kSmall.views() * 3 * 5 * 7, 9),
             [](hid_t dcpl) { H5Pset_szip(dcpl, H5_SZIP_NN_OPTION_MASK, 4); });
  auto read = readLightField(path);
  expectErrorMentioning(read, "szip parameters out of range");
  EXPECT_EQ(read.error().code, ErrorCode::Format);
}

// Writes /lightfield as lfcam 1 did: float32, one chunk per view, shuffle and deflate applied by
// libhdf5, lfcam_version 1, no encoding attribute.
void writeVersion1File(const fs::path& path, const LightField& lf) {
  const LightFieldShape& shape = lf.shape();
  const hsize_t dims[5] = {hsize_t(shape.nv), hsize_t(shape.nu), hsize_t(shape.channels), hsize_t(shape.nt),
                           hsize_t(shape.ns)};
  const hsize_t chunk[5] = {1, 1, dims[2], dims[3], dims[4]};
  hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(dcpl, 5, chunk);
  H5Pset_shuffle(dcpl);
  H5Pset_deflate(dcpl, 1);
  hid_t space = H5Screate_simple(5, dims, nullptr);
  hid_t data = H5Dcreate2(file, "lightfield", H5T_IEEE_F32LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  H5Dwrite(data, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, lf.samples().data());
  hid_t scalar = H5Screate(H5S_SCALAR);
  hid_t version = H5Acreate2(file, "lfcam_version", H5T_STD_I32LE, scalar, H5P_DEFAULT, H5P_DEFAULT);
  const int one = 1;
  H5Awrite(version, H5T_NATIVE_INT, &one);
  H5Aclose(version), H5Sclose(scalar), H5Dclose(data), H5Sclose(space), H5Pclose(dcpl), H5Fclose(file);
}

TEST(LightFieldIoHdf5, FilesOfTheFirstVersionStillRead) {
  test::TempDir dir;
  const LightField lf = randomLightField(kSmall, 9, Quantise::Srgb8);
  writeVersion1File(dir / "v1.lf.h5", lf);
  auto read = readLightField(dir / "v1.lf.h5");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(maxDifference(*read, lf), 0.0f);
}

// A filter HDF5 does not know in the reading process: one line naming it, not libhdf5's stack.
TEST(LightFieldIoHdf5, AMissingFilterPluginIsOneClearError) {
  test::TempDir dir;
  constexpr H5Z_filter_t kTestFilter = 300;  // in HDF5's range for testing
  const H5Z_class2_t identity = {H5Z_CLASS_T_VERS,
                                 kTestFilter,
                                 1,
                                 1,
                                 "lfcam test filter",
                                 nullptr,
                                 nullptr,
                                 [](unsigned, std::size_t, const unsigned[], std::size_t bytes, std::size_t*,
                                    void**) -> std::size_t { return bytes; }};
  ASSERT_GE(H5Zregister(&identity), 0);
  const LightField lf = randomLightField(kSmall, 10);
  {
    const hsize_t dims[5] = {2, 3, 3, 5, 7}, chunk[5] = {1, 1, 3, 5, 7};
    hid_t file = H5Fcreate((dir / "plugin.lf.h5").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, 5, chunk);
    H5Pset_filter(dcpl, kTestFilter, H5Z_FLAG_MANDATORY, 0, nullptr);
    hid_t space = H5Screate_simple(5, dims, nullptr);
    hid_t data = H5Dcreate2(file, "lightfield", H5T_IEEE_F32LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    ASSERT_GE(H5Dwrite(data, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, lf.samples().data()), 0);
    H5Dclose(data), H5Sclose(space), H5Pclose(dcpl), H5Fclose(file);
  }
  auto read = readLightField(dir / "plugin.lf.h5");  // readable while the filter is there
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(maxDifference(*read, lf), 0.0f);
  ASSERT_GE(H5Zunregister(kTestFilter), 0);
  read = readLightField(dir / "plugin.lf.h5");
  expectErrorMentioning(read, "plugin.lf.h5");
  expectErrorMentioning(read, "filter 300 (lfcam test filter)");
  EXPECT_EQ(read.error().code, ErrorCode::Unsupported);
}

// An integer dataset of the given type with the given attributes, as a careless or hostile tool
// might write it.
void writeCodesFile(const fs::path& path, hid_t type, const char* encoding, std::optional<double> scale) {
  const hsize_t dims[5] = {1, 2, 1, 4, 4};
  hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  hid_t space = H5Screate_simple(5, dims, nullptr);
  hid_t data = H5Dcreate2(file, "lightfield", type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  std::vector<unsigned> codes(32, 7);
  H5Dwrite(data, H5T_NATIVE_UINT, H5S_ALL, H5S_ALL, H5P_DEFAULT, codes.data());
  hid_t scalar = H5Screate(H5S_SCALAR);
  if (encoding) {
    hid_t stringType = H5Tcopy(H5T_C_S1);
    H5Tset_size(stringType, std::strlen(encoding) + 1);
    hid_t attribute = H5Acreate2(data, "encoding", stringType, scalar, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(attribute, stringType, encoding);
    H5Aclose(attribute), H5Tclose(stringType);
  }
  if (scale) {
    hid_t attribute = H5Acreate2(data, "scale", H5T_IEEE_F64LE, scalar, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(attribute, H5T_NATIVE_DOUBLE, &*scale);
    H5Aclose(attribute);
  }
  H5Sclose(scalar), H5Dclose(data), H5Sclose(space), H5Fclose(file);
}

TEST(LightFieldIoHdf5, IntegerCodesNeedAnEncodingThatFitsThem) {
  test::TempDir dir;
  writeCodesFile(dir / "good.h5", H5T_STD_U16LE, "linear", 0.5);  // as h5py might write it
  auto good = readLightField(dir / "good.h5");
  ASSERT_TRUE(good) << good.error().message;
  EXPECT_EQ(good->at(1, 0, 3, 3, 0), 3.5f);
  writeCodesFile(dir / "srgb.h5", H5T_STD_U8LE, "srgb8", std::nullopt);
  auto srgb = readLightField(dir / "srgb.h5");
  ASSERT_TRUE(srgb) << srgb.error().message;
  EXPECT_EQ(srgb->at(0, 0, 0, 0, 0), linearFromSrgb(7 / 255.0f));

  struct Case {
    const char* file;
    hid_t type;
    const char* encoding;
    std::optional<double> scale;
    const char* mentioned;
  };
  const Case cases[] = {
      {"no-encoding.h5", H5T_STD_U8LE, nullptr, std::nullopt, "without an 'encoding'"},
      {"wide-srgb.h5", H5T_STD_U16LE, "srgb8", std::nullopt, "8-bit unsigned"},
      {"signed.h5", H5T_STD_I16LE, "linear", 1.0, "unsigned"},
      {"wide.h5", H5T_STD_U32LE, "linear", 1.0, "unsigned"},
      {"no-scale.h5", H5T_STD_U8LE, "linear", std::nullopt, "scale"},
      {"nan-scale.h5", H5T_STD_U8LE, "linear", NAN, "scale"},
      {"negative-scale.h5", H5T_STD_U8LE, "linear", -1.0, "scale"},
      {"huge-scale.h5", H5T_STD_U8LE, "linear", 1e300, "scale"},
      {"unknown.h5", H5T_STD_U8LE, "gamma22", std::nullopt, "unknown encoding 'gamma22'"},
  };
  for (const Case& bad : cases) {
    SCOPED_TRACE(bad.file);
    writeCodesFile(dir / bad.file, bad.type, bad.encoding, bad.scale);
    auto read = readLightField(dir / bad.file);
    expectErrorMentioning(read, bad.file);
    expectErrorMentioning(read, bad.mentioned);
  }
}

// Chunks rewritten after the fact: too short, too long, not deflate at all.
TEST(LightFieldIoHdf5, ChunksOfTheWrongSizeOrCorruptAreErrors) {
  test::TempDir dir;
  const LightField lf = randomLightField(kSmall, 11, Quantise::Srgb8);
  const std::vector<unsigned char> view(3 * 5 * 7, 9);
  const std::vector<std::vector<unsigned char>> stored = {
      {view.begin(), view.end() - 1}, std::vector<unsigned char>(view.size() * 2, 9), {0x78, 0x01, 0xff, 0xff}};
  for (std::size_t i = 0; i < stored.size(); ++i) {
    SCOPED_TRACE(i);
    const fs::path path = dir / ("chunk" + std::to_string(i) + ".lf.h5");
    ASSERT_TRUE(writeLightField(path, lf));
    hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    hid_t data = H5Dopen2(file, "lightfield", H5P_DEFAULT);
    const hsize_t offset[5] = {1, 2, 0, 0, 0};
    // Filter mask 0: szip applied (none of these is an szip stream of one view).
    ASSERT_GE(H5Dwrite_chunk(data, H5P_DEFAULT, 0, offset, stored[i].size(), stored[i].data()), 0);
    H5Dclose(data), H5Fclose(file);
    auto read = readLightField(path);
    expectErrorMentioning(read, path.filename().string());
    expectErrorMentioning(read, "view 5");
    EXPECT_EQ(read.error().code, ErrorCode::Format);
  }
}

TEST(LightFieldIoHdf5, GarbageAndTruncatedFilesAreErrors) {
  test::TempDir dir;
  test::writeBytes(dir / "garbage.lf.h5", "this is not a light field\n");
  expectErrorMentioning(readLightField(dir / "garbage.lf.h5"), "garbage.lf.h5");

  const LightField lf = randomLightField(kSmall, 4);
  ASSERT_TRUE(writeLightField(dir / "full.lf.h5", lf));
  const std::string bytes = test::readBytes(dir / "full.lf.h5");
  test::writeBytes(dir / "cut.lf.h5", bytes.substr(0, bytes.size() / 2));
  expectErrorMentioning(readLightField(dir / "cut.lf.h5"), "cut.lf.h5");
  test::writeBytes(dir / "head.lf.h5", bytes.substr(0, 600));
  expectErrorMentioning(readLightField(dir / "head.lf.h5"), "head.lf.h5");
}

TEST(LightFieldIoDetection, ByContentNotByName) {
  test::TempDir dir;
  const LightField lf = randomLightField(kSmall, 5);
  ASSERT_TRUE(writeLightField(dir / "lf.h5", lf));
  fs::rename(dir / "lf.h5", dir / "looks-like.png");
  auto format = detectLightFieldFormat(dir / "looks-like.png");
  ASSERT_TRUE(format) << format.error().message;
  EXPECT_EQ(*format, LightFieldFormat::Hdf5);
  auto read = readLightField(dir / "looks-like.png");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(maxDifference(*read, lf), 0.0f);

  // A lenslet PNG named .h5 is still an image.
  ASSERT_TRUE(writeLightField(dir / "lenslet.png", lf));
  fs::rename(dir / "lenslet.png", dir / "lenslet.h5");
  format = detectLightFieldFormat(dir / "lenslet.h5");
  ASSERT_TRUE(format);
  EXPECT_EQ(*format, LightFieldFormat::LensletImage);
}

// ---- folders ----

TEST(LightFieldIoHci, EightBitRoundTripIsExactWithParameters) {
  test::TempDir dir;
  LightField lf = randomLightField(kSmall, 6, Quantise::Srgb8);
  lf.metadata.disparityMin = -3.3;
  lf.metadata.disparityMax = 2.8;
  const fs::path folder = dir / "hci";
  ProgressLog writeLog, readLog;
  ASSERT_TRUE(writeLightField(folder, lf, {}, writeLog.callback()));
  writeLog.expectComplete();
  EXPECT_EQ(namesIn(folder),
            (std::set<std::string>{"input_Cam000.png", "input_Cam001.png", "input_Cam002.png", "input_Cam003.png",
                                   "input_Cam004.png", "input_Cam005.png", "parameters.cfg"}));
  const std::string config = test::readBytes(folder / "parameters.cfg");
  for (const char* line : {"num_cams_x = 3", "num_cams_y = 2", "image_resolution_x_px = 7", "image_resolution_y_px = 5",
                           "disp_min = -3.3", "disp_max = 2.8"})
    EXPECT_NE(config.find(line), std::string::npos) << line << " in\n" << config;
  // View index = v * nu + u.
  auto view5 = readImage(folder / "input_Cam005.png");
  ASSERT_TRUE(view5);
  EXPECT_EQ(view5->at(6, 4, 2), lf.at(2, 1, 6, 4, 2));

  auto read = readLightField(folder, {}, readLog.callback());
  ASSERT_TRUE(read) << read.error().message;
  readLog.expectComplete();
  EXPECT_EQ(maxDifference(*read, lf), 0.0f);
  EXPECT_EQ(read->metadata.disparityMin, -3.3);
  EXPECT_EQ(read->metadata.disparityMax, 2.8);
  auto info = probeLightField(folder);
  ASSERT_TRUE(info);
  EXPECT_EQ(info->format, LightFieldFormat::HciFolder);
  EXPECT_EQ(info->shape, kSmall);
}

TEST(LightFieldIoHci, SixteenBitIsLinearWithinOneCode) {
  test::TempDir dir;
  const LightField lf = randomLightField(kSmall, 7);
  ASSERT_TRUE(writeLightField(dir / "hci16", lf, {.sampleType = SampleType::UInt16}));
  auto header = readImageHeader(dir / "hci16" / "input_Cam000.png");
  ASSERT_TRUE(header);
  EXPECT_EQ(header->sampleType, SampleType::UInt16);
  auto read = readLightField(dir / "hci16");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_LE(maxDifference(*read, lf), 0.5f / 65535.0f + 1e-7f);
}

TEST(LightFieldIoHci, SquareGridWithoutParametersAndViewsSubfolder) {
  test::TempDir dir;
  const LightField lf = randomLightField({.nu = 2, .nv = 2, .ns = 4, .nt = 3, .channels = 1}, 8, Quantise::Srgb8);
  // Views in views/, parameters.cfg beside the views folder.
  ASSERT_TRUE(writeLightField(dir / "scene" / "views", lf));
  fs::rename(dir / "scene" / "views" / "parameters.cfg", dir / "scene" / "parameters.cfg");
  auto read = readLightField(dir / "scene");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(maxDifference(*read, lf), 0.0f);
  // Without parameters.cfg, four views make a 2x2 grid.
  fs::remove(dir / "scene" / "parameters.cfg");
  read = readLightField(dir / "scene");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(maxDifference(*read, lf), 0.0f);
}

// An HCI folder of 3x3 views of 6x4 pixels to damage.
fs::path goodHciFolder(const test::TempDir& dir) {
  const fs::path folder = dir / "hci";
  EXPECT_TRUE(writeLightField(folder, randomLightField({.nu = 3, .nv = 3, .ns = 6, .nt = 4, .channels = 3}, 9)));
  return folder;
}

TEST(LightFieldIoHci, BadFoldersAreErrorsNamingTheFile) {
  {
    test::TempDir dir;
    const fs::path folder = goodHciFolder(dir);
    fs::remove(folder / "input_Cam004.png");
    expectErrorMentioning(readLightField(folder), "input_Cam004.png");
  }
  {
    test::TempDir dir;
    const fs::path folder = goodHciFolder(dir);
    ASSERT_TRUE(writeImage(folder / "input_Cam005.png", Image(7, 4, 3)));
    expectErrorMentioning(readLightField(folder), "input_Cam005.png");
    expectErrorMentioning(probeLightField(folder), "input_Cam005.png");  // headers are checked too
  }
  {
    test::TempDir dir;
    const fs::path folder = goodHciFolder(dir);
    ASSERT_TRUE(writeImage(folder / "input_Cam006.png", Image(6, 4, 1)));
    auto read = readLightField(folder);
    expectErrorMentioning(read, "input_Cam006.png");
    expectErrorMentioning(read, "channels");
  }
  {
    test::TempDir dir;
    const fs::path folder = goodHciFolder(dir);
    const std::string bytes = test::readBytes(folder / "input_Cam007.png");
    test::writeBytes(folder / "input_Cam007.png", bytes.substr(0, bytes.size() / 2));
    expectErrorMentioning(readLightField(folder), "input_Cam007.png");
    expectErrorMentioning(probeLightField(folder), "input_Cam007.png");
  }
  {
    test::TempDir dir;
    const fs::path folder = goodHciFolder(dir);
    fs::copy_file(folder / "input_Cam000.png", folder / "input_Cam009.png");
    expectErrorMentioning(readLightField(folder), "input_Cam009.png");
  }
  {
    test::TempDir dir;
    const fs::path folder = goodHciFolder(dir);
    fs::remove(folder / "parameters.cfg");
    fs::remove(folder / "input_Cam008.png");
    expectErrorMentioning(readLightField(folder), "square");
  }
  {
    test::TempDir dir;
    const fs::path folder = goodHciFolder(dir);
    test::writeBytes(folder / "parameters.cfg", "[extrinsics]\nnum_cams_x = three\nnum_cams_y = 3\n");
    expectErrorMentioning(readLightField(folder), "parameters.cfg");
  }
  {
    test::TempDir dir;
    const fs::path folder = goodHciFolder(dir);
    fs::remove(folder / "input_Cam003.png");
    fs::create_directories(folder / "input_Cam003.png");  // a folder where a view should be
    expectErrorMentioning(readLightField(folder), "input_Cam003.png");
  }
}

TEST(LightFieldIoRowColumn, RoundTripAndNames) {
  test::TempDir dir;
  const LightField lf = randomLightField(kSmall, 10, Quantise::Srgb8);
  const fs::path folder = dir / "rc";
  ASSERT_TRUE(writeLightField(folder, lf, {.format = LightFieldFormat::RowColumnFolder}));
  EXPECT_EQ(namesIn(folder), (std::set<std::string>{"view_01_01.png", "view_01_02.png", "view_01_03.png",
                                                    "view_02_01.png", "view_02_02.png", "view_02_03.png"}));
  auto view = readImage(folder / "view_02_03.png");  // row 2 = v 1, column 3 = u 2
  ASSERT_TRUE(view);
  EXPECT_EQ(view->at(3, 2, 0), lf.at(2, 1, 3, 2, 0));
  auto read = readLightField(folder);
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(maxDifference(*read, lf), 0.0f);
  auto format = detectLightFieldFormat(folder);
  ASSERT_TRUE(format);
  EXPECT_EQ(*format, LightFieldFormat::RowColumnFolder);

  const LightField deep = randomLightField(kSmall, 11, Quantise::Linear16);
  ASSERT_TRUE(writeLightField(dir / "rc16", deep,
                              {.format = LightFieldFormat::RowColumnFolder, .sampleType = SampleType::UInt16}));
  read = readLightField(dir / "rc16");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(maxDifference(*read, deep), 0.0f);
}

// Float views (TIFF, OpenEXR) in either layout read back exactly, beyond [0, 1] too; a folder
// holding the same view twice (view_01_01.png and .tif) is refused, not silently resolved.
TEST(LightFieldIoFolders, FloatViewsInTiffAndExrReadBackExactly) {
  test::TempDir dir;
  LightField lf = randomLightField(kSmall, 12);
  lf.samples()[0] = 1.75f;
  lf.samples()[1] = -0.25f;
  for (const char* extension : {".tif", ".tiff", ".exr"})
    for (const LightFieldFormat format : {LightFieldFormat::HciFolder, LightFieldFormat::RowColumnFolder}) {
      const fs::path folder = dir / (std::string(formatName(format)) + extension);
      ASSERT_TRUE(writeLightField(folder, lf,
                                  {.format = format, .sampleType = SampleType::Float32, .viewExtension = extension}));
      auto read = readLightField(folder);
      ASSERT_TRUE(read) << read.error().message;
      EXPECT_EQ(maxDifference(*read, lf), 0.0f) << folder;
    }
  const fs::path folder = dir / "rowcol-folder.exr";
  fs::copy_file(folder / "view_01_01.exr", folder / "view_01_01.png");
  auto both = readLightField(folder);
  ASSERT_FALSE(both);
  EXPECT_NE(both.error().message.find("same view"), std::string::npos) << both.error().message;
  // A depth or an extension the views cannot have is a usage error before anything is written.
  for (const LightFieldWriteOptions& bad :
       {LightFieldWriteOptions{.sampleType = SampleType::Float32},
        LightFieldWriteOptions{.sampleType = SampleType::UInt8, .viewExtension = ".exr"},
        LightFieldWriteOptions{.viewExtension = ".jpg"}}) {
    const Status status = writeLightField(dir / "bad", lf, bad);
    ASSERT_FALSE(status);
    EXPECT_EQ(status.error().code, ErrorCode::Usage) << status.error().message;
    EXPECT_FALSE(fs::exists(dir / "bad"));
  }
}

// Names as the LF Toolbox export of the Lytro set makes them: IMG_0001_NNN_SS_TT.png, SS the
// view's column, TT its row, NNN a counter running down each column and back up the next.
fs::path lytroStyleFolder(const test::TempDir& dir, const LightField& lf) {
  const fs::path views = dir / "capture" / "views";
  fs::create_directories(views);
  int counter = 1;
  for (int column = 1; column <= lf.nu(); ++column)
    for (int step = 0; step < lf.nv(); ++step) {
      const int row = column % 2 == 1 ? step + 1 : lf.nv() - step;
      char name[64];
      std::snprintf(name, sizeof name, "IMG_0001_%03d_%02d_%02d.png", counter++, column, row);
      EXPECT_TRUE(writeImage(views / name, lf.subApertureImage(column - 1, row - 1)));
    }
  return views;
}

TEST(LightFieldIoRowColumn, ColumnFirstNamesWithASerpentineCounter) {
  test::TempDir dir;
  const LightField lf = randomLightField({.nu = 3, .nv = 2, .ns = 4, .nt = 5, .channels = 3}, 12, Quantise::Srgb8);
  const fs::path views = lytroStyleFolder(dir, lf);
  const LightFieldReadOptions columnFirst{.viewNumberOrder = ViewNumberOrder::ColumnFirst};
  auto read = readLightField(dir / "capture", columnFirst);  // views/ found inside
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(maxDifference(*read, lf), 0.0f);
  auto info = probeLightField(views, columnFirst);
  ASSERT_TRUE(info) << info.error().message;
  EXPECT_EQ(info->shape, lf.shape());
  // Read row first, the same files make a 2 x 3 grid: the angular axes swapped.
  auto swapped = readLightField(views, {.viewNumberOrder = ViewNumberOrder::RowFirst});
  ASSERT_TRUE(swapped) << swapped.error().message;
  EXPECT_EQ(swapped->nu(), 2);
  EXPECT_EQ(swapped->nv(), 3);
  EXPECT_EQ(swapped->at(1, 2, 3, 4, 0), lf.at(2, 1, 3, 4, 0));

  // A missing view and a duplicate.
  ASSERT_TRUE(fs::remove(views / "IMG_0001_003_02_02.png"));
  expectErrorMentioning(readLightField(views, columnFirst), "row 2, column 2");
  ASSERT_TRUE(writeImage(views / "other_02_02.png", lf.subApertureImage(1, 1)));
  ASSERT_TRUE(writeImage(views / "more_02_02.png", lf.subApertureImage(1, 1)));
  expectErrorMentioning(readLightField(views, columnFirst), "_02_02.png");
}

// With no order given, the parallax decides: views along a row are displaced horizontally.
TEST(LightFieldIoRowColumn, AutomaticOrderFollowsTheParallax) {
  test::TempDir dir;
  LightField lf = renderLayeredPlanes(defaultLayeredPlanesScene(5, 96)).lightField;
  const fs::path views = lytroStyleFolder(dir, lf);
  auto read = readLightField(views);
  ASSERT_TRUE(read) << read.error().message;
  ASSERT_EQ(read->shape(), lf.shape());
  EXPECT_LT(maxDifference(*read, lf), 0.01f);  // 8-bit quantisation only: every view where it belongs
  // lfcam's own row-first folders stay row-first.
  ASSERT_TRUE(writeLightField(dir / "rowfirst", lf, {.format = LightFieldFormat::RowColumnFolder}));
  auto own = readLightField(dir / "rowfirst");
  ASSERT_TRUE(own) << own.error().message;
  EXPECT_LT(std::abs(own->at(1, 3, 40, 50, 1) - lf.at(1, 3, 40, 50, 1)), 0.01f);
  EXPECT_LT(std::abs(own->at(3, 1, 40, 50, 1) - lf.at(3, 1, 40, 50, 1)), 0.01f);
}

TEST(LightFieldIoFolders, EmptyAndUnrelatedFoldersAreErrors) {
  test::TempDir dir;
  fs::create_directories(dir / "empty");
  auto read = readLightField(dir / "empty");
  expectErrorMentioning(read, "empty");
  EXPECT_EQ(read.error().code, ErrorCode::Format);
  expectErrorMentioning(probeLightField(dir / "empty"), "empty");
  expectErrorMentioning(detectLightFieldFormat(dir / "empty"), "empty");

  fs::create_directories(dir / "unrelated");
  test::writeBytes(dir / "unrelated" / "notes.txt", "hello");
  ASSERT_TRUE(writeImage(dir / "unrelated" / "photo.png", Image(4, 4, 3)));
  expectErrorMentioning(readLightField(dir / "unrelated"), "unrelated");

  auto missing = readLightField(dir / "nothing-here");
  expectErrorMentioning(missing, "nothing-here");
  EXPECT_EQ(missing.error().code, ErrorCode::Io);
}

TEST(LightFieldIoFolders, MixedLayoutsAreRefused) {
  test::TempDir dir;
  const LightField lf = randomLightField(kSmall, 13);
  const fs::path folder = dir / "both";
  ASSERT_TRUE(writeLightField(folder, lf, {.format = LightFieldFormat::RowColumnFolder}));
  // Writing HCI views over row/column ones would make an ambiguous folder.
  Status status = writeLightField(folder, lf);
  ASSERT_FALSE(status);
  EXPECT_EQ(status.error().code, ErrorCode::Usage);
  fs::copy_file(folder / "view_01_01.png", folder / "input_Cam000.png");
  expectErrorMentioning(readLightField(folder), "both");
}

TEST(LightFieldIoFolders, RewritingWithFewerViewsRemovesTheStaleOnes) {
  test::TempDir dir;
  const fs::path folder = dir / "out";
  ASSERT_TRUE(writeLightField(folder, randomLightField({.nu = 3, .nv = 3, .ns = 4, .nt = 4, .channels = 1}, 14)));
  test::writeBytes(folder / "notes.txt", "kept");
  const LightField smaller = randomLightField({.nu = 2, .nv = 2, .ns = 4, .nt = 4, .channels = 1}, 15, Quantise::Srgb8);
  ASSERT_TRUE(writeLightField(folder, smaller));
  EXPECT_EQ(namesIn(folder), (std::set<std::string>{"input_Cam000.png", "input_Cam001.png", "input_Cam002.png",
                                                    "input_Cam003.png", "parameters.cfg", "notes.txt"}));
  auto read = readLightField(folder);
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(maxDifference(*read, smaller), 0.0f);
}

// ---- lenslet images ----

TEST(LightFieldIoLenslet, PixelLayoutAndRoundTrip) {
  test::TempDir dir;
  const LightField lf = randomLightField(kSmall, 16, Quantise::Srgb8);
  ProgressLog writeLog, readLog;
  ASSERT_TRUE(writeLightField(dir / "l.png", lf, {}, writeLog.callback()));
  writeLog.expectComplete();
  auto image = readImage(dir / "l.png");
  ASSERT_TRUE(image);
  EXPECT_EQ(image->width(), 7 * 3);
  EXPECT_EQ(image->height(), 5 * 2);
  for (int v = 0; v < 2; ++v)
    for (int u = 0; u < 3; ++u)
      for (int t = 0; t < 5; ++t)
        for (int s = 0; s < 7; ++s) ASSERT_EQ(image->at(s * 3 + u, t * 2 + v, 1), lf.at(u, v, s, t, 1));
  auto description = readImageDescription(dir / "l.png");
  ASSERT_TRUE(description);
  EXPECT_EQ(*description, "lfcam lenslet nu=3 nv=2");

  auto info = probeLightField(dir / "l.png");
  ASSERT_TRUE(info) << info.error().message;
  EXPECT_EQ(info->format, LightFieldFormat::LensletImage);
  EXPECT_EQ(info->shape, kSmall);
  auto read = readLightField(dir / "l.png", {}, readLog.callback());
  ASSERT_TRUE(read) << read.error().message;
  readLog.expectComplete();
  EXPECT_EQ(maxDifference(*read, lf), 0.0f);
}

TEST(LightFieldIoLenslet, FloatAndSixteenBitFormats) {
  test::TempDir dir;
  const LightField lf = randomLightField(kSmall, 17);
  for (const char* name : {"l.exr", "l.tif"}) {
    ASSERT_TRUE(writeLightField(dir / name, lf)) << name;
    auto read = readLightField(dir / name);
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_LE(maxDifference(*read, lf), std::string(name) == "l.exr" ? 0.0f : 0.5f / 65535.0f + 1e-7f) << name;
  }
  ASSERT_TRUE(writeLightField(dir / "l16.png", lf, {.sampleType = SampleType::UInt16}));
  auto read = readLightField(dir / "l16.png");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_LE(maxDifference(*read, lf), 0.5f / 65535.0f + 1e-7f);
  // PFM has no description: the views per lens are given.
  ASSERT_TRUE(writeLightField(dir / "l.pfm", lf));
  expectErrorMentioning(readLightField(dir / "l.pfm", {.lensletViews = 2}), "l.pfm");  // 21 is not a multiple of 2
}

// A textured scene seen by nu x nv views with parallax and vignetting, as a lenslet image
// written without lfcam's description.
Image syntheticLensletImage(int nu, int nv, int ns, int nt, double disparity) {
  Image image(ns * nu, nt * nv, 1);
  for (int v = 0; v < nv; ++v)
    for (int u = 0; u < nu; ++u) {
      const double du = u - 0.5 * (nu - 1), dv = v - 0.5 * (nv - 1);
      const double vignetting = 1.0 - 0.5 * (du * du + dv * dv) / (0.25 * (nu * nu + nv * nv));
      for (int t = 0; t < nt; ++t)
        for (int s = 0; s < ns; ++s) {
          const double x = s - du * disparity, y = t - dv * disparity;
          const double texture = 0.5 + 0.2 * std::sin(0.31 * x + 0.17 * y) + 0.15 * std::sin(0.07 * x - 0.23 * y) +
                                 0.1 * std::sin(0.5 * x + 0.9 * y);
          image.at(s * nu + u, t * nv + v, 0) = float(vignetting * texture);
        }
    }
  return image;
}

TEST(LightFieldIoLenslet, ViewsPerLensAreEstimatedWhenTheFileDoesNotSay) {
  test::TempDir dir;
  struct Case {
    int nu, nv, ns, nt;
    double disparity;
  };
  for (const Case& c : {Case{9, 9, 40, 30, 0.5}, Case{5, 7, 36, 24, -1.0}, Case{3, 3, 50, 40, 0.0}}) {
    SCOPED_TRACE(std::to_string(c.nu) + "x" + std::to_string(c.nv));
    ASSERT_TRUE(writeImage(dir / "raw.exr", syntheticLensletImage(c.nu, c.nv, c.ns, c.nt, c.disparity)));
    auto info = probeLightField(dir / "raw.exr");
    ASSERT_TRUE(info) << info.error().message;
    EXPECT_EQ(info->shape, (LightFieldShape{.nu = c.nu, .nv = c.nv, .ns = c.ns, .nt = c.nt, .channels = 1}));
    auto read = readLightField(dir / "raw.exr");
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(read->nu(), c.nu);
  }
  // Given views per lens win over the estimate.
  auto given = readLightField(dir / "raw.exr", {.lensletViews = 1});
  ASSERT_TRUE(given) << given.error().message;
  EXPECT_EQ(given->nu(), 1);
}

TEST(LightFieldIoLenslet, AnImageWithoutMacroPixelsAsksForTheViewCount) {
  test::TempDir dir;
  // A photograph-like image: smooth structure at several scales, and a little noise.
  Image plain(120, 90, 3);
  std::mt19937 random(21);
  std::normal_distribution<float> noise(0.0f, 0.01f);
  for (int c = 0; c < 3; ++c)
    for (int y = 0; y < 90; ++y)
      for (int x = 0; x < 120; ++x)
        plain.at(x, y, c) = 0.5f + 0.2f * std::sin(0.05f * x + 0.08f * y + c) + 0.1f * std::sin(0.21f * x - 0.13f * y) +
                            0.05f * std::cos(0.6f * x + 0.35f * y) + noise(random);
  ASSERT_TRUE(writeImage(dir / "photo.png", plain, {.sampleType = SampleType::UInt16}));
  auto read = readLightField(dir / "photo.png");
  expectErrorMentioning(read, "photo.png");
  expectErrorMentioning(read, "views per lens");
  // Its JPEG too: 8-pixel blocks and subsampled chroma do not pass for lenses.
  ASSERT_TRUE(writeImage(dir / "photo.jpg", plain));
  expectErrorMentioning(readLightField(dir / "photo.jpg"), "views per lens");
  // Told, it reads; a count that does not divide the size is an error.
  auto told = readLightField(dir / "photo.png", {.lensletViews = 3});
  ASSERT_TRUE(told) << told.error().message;
  EXPECT_EQ(told->shape(), (LightFieldShape{.nu = 3, .nv = 3, .ns = 40, .nt = 30, .channels = 3}));
  expectErrorMentioning(readLightField(dir / "photo.png", {.lensletViews = 7}), "photo.png");
  expectErrorMentioning(readLightField(dir / "photo.png", {.lensletViews = 0}), "photo.png");
}

// ---- writing ----

TEST(LightFieldIoWrite, FormatFollowsTheNameUnlessOverridden) {
  test::TempDir dir;
  const LightField lf = randomLightField(kSmall, 18);
  ASSERT_TRUE(writeLightField(dir / "a.lf.h5", lf));
  ASSERT_TRUE(writeLightField(dir / "b.png", lf));
  ASSERT_TRUE(writeLightField(dir / "c", lf));
  ASSERT_TRUE(writeLightField(dir / "d.png", lf, {.format = LightFieldFormat::Hdf5}));
  const std::pair<const char*, LightFieldFormat> expected[] = {{"a.lf.h5", LightFieldFormat::Hdf5},
                                                               {"b.png", LightFieldFormat::LensletImage},
                                                               {"c", LightFieldFormat::HciFolder},
                                                               {"d.png", LightFieldFormat::Hdf5}};
  for (const auto& [name, format] : expected) {
    auto detected = detectLightFieldFormat(dir / name);
    ASSERT_TRUE(detected) << name;
    EXPECT_EQ(*detected, format) << name;
  }
}

TEST(LightFieldIoWrite, FailuresLeaveNothingAndNameTheDestination) {
  test::TempDir dir;
  const LightField lf = randomLightField(kSmall, 19);
  for (const char* name : {"missing/a.lf.h5", "missing/b.png"}) {
    Status status = writeLightField(dir / name, lf);
    ASSERT_FALSE(status) << name;
    EXPECT_NE(status.error().message.find(name), std::string::npos) << status.error().message;
  }
  fs::create_directories(dir / "taken.lf.h5");
  EXPECT_FALSE(writeLightField(dir / "taken.lf.h5", lf));
  expectErrorMentioning(readLightField(dir / "taken.lf.h5"), "taken.lf.h5");  // an empty folder
  // A light field PNG cannot hold: five channels.
  Status status =
      writeLightField(dir / "five", randomLightField({.nu = 2, .nv = 1, .ns = 2, .nt = 2, .channels = 5}, 20));
  ASSERT_FALSE(status);
  EXPECT_NE(status.error().message.find("five"), std::string::npos) << status.error().message;
  EXPECT_EQ(status.error().message.find(".lfcam-tmp"), std::string::npos) << status.error().message;
  EXPECT_FALSE(writeLightField(dir / "empty.lf.h5", LightField()));
  EXPECT_EQ(namesIn(dir.path()), (std::set<std::string>{"taken.lf.h5"}));
}

}  // namespace
}  // namespace lfcam
