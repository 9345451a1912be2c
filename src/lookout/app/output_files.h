#pragma once

#include <string>
#include <string_view>

namespace lookout::app {

// Writes `contents` to `path` through a temporary file beside it and a rename, so that a
// reader never sees half a file and a failed run leaves none. Throws std::runtime_error.
void WriteFileAtomically(const std::string& path, std::string_view contents);

// Creates `dir` (and its parents) if needed; throws lookout::InputError(flag, ...) when a
// non-directory is in the way or it cannot be made.
void EnsureOutputDirectory(const std::string& dir, const std::string& flag);

}  // namespace lookout::app
