// Heavy libraries that few commands need (FFmpeg for MP4, LibRaw for camera raws) live in shared
// modules built with lfcam, liblfcam_NAME.so, loaded on first use so that start-up maps none of
// them (docs/design.md, "Start-up"). The dynamic loader finds a module through the executable's run
// path, which lfcam's build sets to its module folder and its installed CMake package to
// PREFIX/lib/lfcam, or through LD_LIBRARY_PATH.
#pragma once

#include <string>

#include "lfcam/core/result.hpp"

namespace lfcam {

// The address of `entry` in module `name` ("mp4" for liblfcam_mp4.so): a module exports one table
// of functions (a C++ struct declared beside its user) as a C symbol. Else an Unsupported error
// saying that `purpose` ("MP4 export") needs the module and why it cannot be loaded.
Result<void*> lazyModuleEntry(const std::string& name, const char* entry, const std::string& purpose);

}  // namespace lfcam
