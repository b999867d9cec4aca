// What io's HDF5 files share (the light field's, the volume's): the library's lock, errors that
// name the file and give libhdf5's own reason, file access, attributes, and the throwaway process
// that first makes libhdf5's calls on an untrusted file.
#pragma once

#include <hdf5.h>

#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "core/hdf5_handle.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam::io {

// Holds the library's one HDF5 lock (core/hdf5_lock.hpp) and keeps HDF5 from printing its error
// stack to stderr.
class Hdf5Session {
 public:
  Hdf5Session();

  // Runs `work`, which makes no HDF5 call, with the lock released: lfcam's threads encode or
  // decode samples meanwhile, and a task of another HDF5 user that one of them picks up cannot
  // wait for a lock its own thread holds.
  template <class Work>
  auto unlockedWhile(Work&& work) {
    lock_.unlock();
    struct Relock {
      std::unique_lock<std::mutex>& lock;
      ~Relock() { lock.lock(); }
    } relock{lock_};
    return work();
  }

 private:
  std::unique_lock<std::mutex> lock_;
};

// The HDF5 signature at offset 0 or at a user-block offset (512, 1024, 2048, ...).
bool startsLikeHdf5(const std::filesystem::path& path);

// "path: what: reason", the reason the innermost message on HDF5's error stack ("file signature
// not found"); clears the stack.
Error hdf5Error(ErrorCode code, const std::filesystem::path& path, const std::string& what);

// File access: tolerate file systems without locking (network mounts) instead of failing.
hdf5::Handle fileAccess();

// An attribute of `object`, unset when absent; one of another type or size is a Format error.
Result<std::optional<std::string>> readStringAttribute(const std::filesystem::path& path, hid_t object,
                                                       const char* name);
Result<std::optional<double>> readNumberAttribute(const std::filesystem::path& path, hid_t object, const char* name);
// Any number of numbers (a scalar is one).
Result<std::optional<std::vector<double>>> readNumbersAttribute(const std::filesystem::path& path, hid_t object,
                                                                const char* name);

bool writeStringAttribute(hid_t object, const char* name, const std::string& value);
template <class T>
bool writeScalarAttribute(hid_t object, const char* name, hid_t fileType, hid_t memoryType, T value) {
  hdf5::Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  hdf5::Handle attribute(H5Acreate2(object, name, fileType, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  return attribute.valid() && H5Awrite(attribute.get(), memoryType, &value) >= 0;
}
// A one-dimensional float64 attribute.
bool writeNumbersAttribute(hid_t object, const char* name, const std::vector<double>& values);

// Makes an HDF5 file in memory, `fill` creating its contents, then writes its bytes to `file`;
// errors name `reportAs`. libhdf5 1.10 does not survive its own failed writes (a full disk left a
// file whose close crashed the process at exit): here it never touches the disk, lfcam does.
Status writeHdf5ThroughMemory(const std::filesystem::path& file, const std::filesystem::path& reportAs,
                              const std::function<Status(hid_t file)>& fill);

// Runs `calls` (the HDF5 calls a reader will make on `path`) in a throwaway process first
// (survives_in_child.hpp): fuzzing found memory errors inside libhdf5 1.10 on corrupt files. A
// child that dies or hangs gets the file refused with a Format error.
Status refuseWhatCrashesLibhdf5(const std::filesystem::path& path, const std::function<void()>& calls);

}  // namespace lfcam::io
