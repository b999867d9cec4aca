// Not compiled: the test module_includes_catch_a_leak checks this file as if it were in
// src/calibrate/, where an include of the depth module's internals must be refused.
#include "edof/edof_internal.hpp"
