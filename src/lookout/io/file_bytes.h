#pragma once

// A whole binary file as bytes, for the readers of formats held in memory (ROS bags, zip).

#include <string>

namespace lookout::io {

// Throws lookout::InputError naming `path` when it cannot be opened or read.
std::string ReadFileBytes(const std::string& path);

}  // namespace lookout::io
