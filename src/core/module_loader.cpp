#include "core/module_loader.h"

#include <dlfcn.h>

#include <filesystem>

#include "rangefill/core/errors.h"

namespace rangefill {

void* module_entry(const char* module, const char* entry, const void* anchor,
                   const std::string& what) {
  Dl_info library;
  if (dladdr(anchor, &library) == 0 || !library.dli_fname) {
    throw ProcessingError(what + ": cannot tell where the library that needs " + module + " is");
  }
  const std::string path =
      (std::filesystem::path(library.dli_fname).parent_path() / module).string();
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  void* symbol = handle ? dlsym(handle, entry) : nullptr;
  if (!symbol) {
    const char* error = dlerror();
    throw ProcessingError(what + ": cannot load " + path + ": " +
                          (error ? error : std::string(entry) + " is null"));
  }
  return symbol;
}

}  // namespace rangefill
