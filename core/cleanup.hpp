#pragma once
#include <string>

namespace clatter {

// Paths of in-progress temporary outputs. When a run dies on an error path that skips destructors
// (MPI_Abort), the handler removes them first, so no partial file survives under any name.
void register_temporary(const std::string& path);
void unregister_temporary(const std::string& path);
// Removes every registered path (best effort, no throw). Returns how many were removed.
int remove_registered_temporaries() noexcept;

}  // namespace clatter
