#pragma once

#include <string>
#include <string_view>

namespace lookout::app {

// Writes `contents` to `path` through a temporary file beside it and a rename, so that a
// reader never sees half a file and a failed run leaves none. Throws std::runtime_error.
void WriteFileAtomically(const std::string& path, std::string_view contents);

// An output file's directory must exist and the path must not be a directory: checked before a
// run, so that a typo costs nothing and leaves nothing behind. Throws lookout::InputError(path,
// 0, flag, ...); an empty path (no such output) passes.
void CheckOutputFilePath(const std::string& path, const std::string& flag);

// Creates `dir` (and its parents) if needed; throws lookout::InputError(flag, ...) when a
// non-directory is in the way or it cannot be made.
void EnsureOutputDirectory(const std::string& dir, const std::string& flag);

}  // namespace lookout::app
