// Internal: the modules installed beside the libraries, shared objects loaded (dlopen) when first
// needed, so that no program pays at start-up for the libraries they link (VTK, Ceres).
#pragma once

#include <string>

namespace rangefill {

/// The address of the function `entry` in `module`, a file in the directory of the shared object
/// that holds `anchor` (a function of the calling library). Throws ProcessingError ("`what`:
/// cannot load ...") when the module or its entry cannot be loaded.
void* module_entry(const char* module, const char* entry, const void* anchor,
                   const std::string& what);

}  // namespace rangefill
