// numpy arrays over lfcam's buffers, without copying, and lfcam values from numpy arrays.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"

namespace lfcam::python {

// A float32 array over `data` with this shape (C order), kept alive by `owner`.
pybind11::array viewOf(float* data, std::vector<pybind11::ssize_t> shape, pybind11::handle owner);

// A numeric array as float32 in C order (a copy only when its dtype or layout is another), after
// checking its rank is one of `ranks`; `what` names the argument in the error.
pybind11::array_t<float, pybind11::array::c_style> floatArray(const pybind11::array& array,
                                                              std::initializer_list<int> ranks, const char* what);

// An Image from an array of shape (height, width) or (channels, height, width).
Image imageFromArray(const pybind11::array& array, const char* what);

void bindArrays(pybind11::module_& module);

}  // namespace lfcam::python
