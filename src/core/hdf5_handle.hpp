// An HDF5 identifier closed by the matching function when it goes out of scope, for every module
// that calls HDF5 (io's light-field files, lfm's PSF cache). Header only: core does not link HDF5;
// its users do. Internal to the library.
#pragma once

#include <hdf5.h>

namespace lfcam::hdf5 {

// An HDF5 identifier closed by the matching function when it goes out of scope.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  Handle(Handle&& other) noexcept : id_(other.id_), close_(other.close_) { other.id_ = -1; }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  // Closes now, reporting failure (a file's last metadata is written when it closes).
  bool close() {
    const bool ok = id_ < 0 || close_(id_) >= 0;
    id_ = -1;
    return ok;
  }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

}  // namespace lfcam::hdf5
