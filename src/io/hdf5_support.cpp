#include "io/hdf5_support.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>

#include "core/hdf5_lock.hpp"
#include "io/io_support.hpp"
#include "io/survives_in_child.hpp"

namespace lfcam::io {

namespace fs = std::filesystem;
using hdf5::Handle;

namespace {

// The innermost message on HDF5's error stack: the actual reason ("file signature not found").
// Walking downward goes from the API call to where the error arose, so the last entry wins.
std::string hdf5Reason() {
  std::string reason;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_DOWNWARD,
      [](unsigned, const H5E_error2_t* error, void* data) -> herr_t {
        if (error->desc && *error->desc) *static_cast<std::string*>(data) = error->desc;
        return 0;
      },
      &reason);
  H5Eclear2(H5E_DEFAULT);
  return reason.empty() ? "unknown HDF5 error" : reason;
}

}  // namespace

Hdf5Session::Hdf5Session() : lock_(hdf5::libraryMutex()) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  H5Eclear2(H5E_DEFAULT);
}

bool startsLikeHdf5(const fs::path& path) {
  static constexpr unsigned char kSignature[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return false;
  const std::uintmax_t size = fs::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  for (std::uintmax_t offset = 0; !ec && in && offset + 8 <= size; offset = offset == 0 ? 512 : offset * 2) {
    unsigned char head[8] = {};
    in.seekg(std::streamoff(offset));
    in.read(reinterpret_cast<char*>(head), 8);
    if (in.gcount() == 8 && std::memcmp(head, kSignature, 8) == 0) return true;
  }
  return false;
}

Error hdf5Error(ErrorCode code, const fs::path& path, const std::string& what) {
  return fileError(code, path, what + ": " + hdf5Reason());
}

Handle fileAccess() {
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5Pset_file_locking(fapl.get(), true, true);
  return fapl;
}

Result<std::optional<std::string>> readStringAttribute(const fs::path& path, hid_t object, const char* name) {
  if (H5Aexists(object, name) <= 0) return std::optional<std::string>();
  Handle attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
  Handle type(H5Aget_type(attribute.get()), H5Tclose);
  Handle space(H5Aget_space(attribute.get()), H5Sclose);
  if (!attribute.valid() || !type.valid() || H5Tget_class(type.get()) != H5T_STRING ||
      H5Sget_simple_extent_npoints(space.get()) != 1)
    return fileError(ErrorCode::Format, path, std::string("attribute '") + name + "' is not a string");
  // libhdf5 1.10 copies a variable-length string's global-heap object into a buffer sized by the
  // attribute's own length field, so a file whose two disagree overflows the heap inside H5Aread
  // (fuzz/regressions/hdf5_light_field). lfcam writes fixed-length strings and refuses the others.
  if (H5Tis_variable_str(type.get()) != 0)
    return fileError(ErrorCode::Unsupported, path,
                     std::string("attribute '") + name +
                         "' is a variable-length string; lfcam reads fixed-length string attributes only");
  const std::size_t size = H5Tget_size(type.get());
  if (size == 0 || size > (1u << 20))
    return fileError(ErrorCode::Format, path, std::string("attribute '") + name + "' has a bad size");
  std::vector<char> text(size + 1, '\0');
  if (H5Aread(attribute.get(), type.get(), text.data()) < 0)
    return hdf5Error(ErrorCode::Format, path, std::string("cannot read attribute '") + name + "'");
  return std::optional<std::string>(std::string(text.data()));  // up to the first NUL
}

Result<std::optional<std::vector<double>>> readNumbersAttribute(const fs::path& path, hid_t object, const char* name) {
  if (H5Aexists(object, name) <= 0) return std::optional<std::vector<double>>();
  Handle attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
  Handle type(H5Aget_type(attribute.get()), H5Tclose);
  Handle space(H5Aget_space(attribute.get()), H5Sclose);
  const H5T_class_t typeClass = type.valid() ? H5Tget_class(type.get()) : H5T_NO_CLASS;
  const hssize_t count = space.valid() ? H5Sget_simple_extent_npoints(space.get()) : -1;
  if (!attribute.valid() || (typeClass != H5T_FLOAT && typeClass != H5T_INTEGER) || count < 1 || count > (1 << 20))
    return fileError(ErrorCode::Format, path, std::string("attribute '") + name + "' is not a number");
  std::vector<double> values(static_cast<std::size_t>(count));
  if (H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, values.data()) < 0)
    return hdf5Error(ErrorCode::Format, path, std::string("cannot read attribute '") + name + "'");
  return std::optional(std::move(values));
}

Result<std::optional<double>> readNumberAttribute(const fs::path& path, hid_t object, const char* name) {
  LFCAM_ASSIGN_OR_RETURN(auto values, readNumbersAttribute(path, object, name));
  if (!values) return std::optional<double>();
  if (values->size() != 1)
    return fileError(ErrorCode::Format, path, std::string("attribute '") + name + "' is not a number");
  return std::optional<double>(values->front());
}

bool writeStringAttribute(hid_t object, const char* name, const std::string& value) {
  // Fixed-length UTF-8, NUL-padded (see readStringAttribute for why not variable-length): h5py
  // reads it as bytes, MATLAB's h5readatt as char.
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), std::max<std::size_t>(value.size(), 1));
  H5Tset_strpad(type.get(), H5T_STR_NULLPAD);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attribute(H5Acreate2(object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  std::string padded = value;
  padded.resize(std::max<std::size_t>(value.size(), 1), '\0');
  return attribute.valid() && H5Awrite(attribute.get(), type.get(), padded.data()) >= 0;
}

bool writeNumbersAttribute(hid_t object, const char* name, const std::vector<double>& values) {
  const hsize_t count = values.size();
  Handle space(H5Screate_simple(1, &count, nullptr), H5Sclose);
  Handle attribute(H5Acreate2(object, name, H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  return attribute.valid() && H5Awrite(attribute.get(), H5T_NATIVE_DOUBLE, values.data()) >= 0;
}

Status writeHdf5ThroughMemory(const fs::path& file, const fs::path& path,
                              const std::function<Status(hid_t file)>& fill) {
  constexpr std::size_t kGrowth = std::size_t(16) << 20;  // the in-memory file grows by this much at a time
  std::vector<char> image;
  {
    Hdf5Session session;
    Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
    H5Pset_fapl_core(fapl.get(), kGrowth, false);  // no backing store: the file is the memory image only
    Handle handle(H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose);
    if (!handle.valid()) return hdf5Error(ErrorCode::Io, path, "cannot create");
    LFCAM_TRY(fill(handle.get()));
    if (H5Fflush(handle.get(), H5F_SCOPE_GLOBAL) < 0) return hdf5Error(ErrorCode::Io, path, "cannot write");
    const ssize_t size = H5Fget_file_image(handle.get(), nullptr, 0);
    if (size > 0) image.resize(std::size_t(size));
    if (size <= 0 || H5Fget_file_image(handle.get(), image.data(), image.size()) != size || !handle.close())
      return hdf5Error(ErrorCode::Io, path, "cannot write");
  }
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) return fileError(ErrorCode::Io, path, "cannot create: " + std::string(std::strerror(errno)));
  out.write(image.data(), std::streamsize(image.size()));
  out.close();
  if (!out) return fileError(ErrorCode::Io, path, "cannot write: " + std::string(std::strerror(errno)));
  return {};
}

Status refuseWhatCrashesLibhdf5(const fs::path& path, const std::function<void()>& calls) {
  const ChildOutcome outcome = survivesInChild(calls, std::chrono::seconds(30));
  if (outcome == ChildOutcome::Crashed)
    return fileError(ErrorCode::Format, path,
                     "a corrupt HDF5 file: libhdf5 crashed reading it (in a throwaway process)");
  if (outcome == ChildOutcome::TimedOut)
    return fileError(ErrorCode::Format, path, "a corrupt HDF5 file: libhdf5 did not finish reading it within 30 s");
  return {};
}

}  // namespace lfcam::io
