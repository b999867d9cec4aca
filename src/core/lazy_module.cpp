#include "core/lazy_module.hpp"

#include <dlfcn.h>

namespace lfcam {

Result<void*> lazyModuleEntry(const std::string& name, const char* entry, const std::string& purpose) {
  const std::string file = "liblfcam_" + name + ".so";
  // dlopen counts references: a module already loaded comes back at once, and is never unloaded.
  void* module = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  const char* problem = nullptr;
  void* address = nullptr;
  if (!module)
    problem = dlerror();
  else if (!(address = dlsym(module, entry)))
    problem = dlerror();
  if (problem)
    return makeError(ErrorCode::Unsupported,
                     purpose + " needs lfcam's module " + file + ", which cannot be loaded: " + problem);
  return address;
}

}  // namespace lfcam
