#include "lookout/app/output_files.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

#include "lookout/core/input_error.h"

namespace lookout::app {

void WriteFileAtomically(const std::string& path, std::string_view contents) {
  const std::string part = path + ".part";
  {
    std::ofstream out(part, std::ios::binary | std::ios::trunc);
    out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    if (!out) throw std::runtime_error("cannot write " + part);
  }
  std::error_code ec;
  std::filesystem::rename(part, path, ec);
  if (ec) {
    std::filesystem::remove(part, ec);
    throw std::runtime_error("cannot rename " + part + " to " + path);
  }
}

void CheckOutputFilePath(const std::string& path, const std::string& flag) {
  if (path.empty()) return;
  const std::filesystem::path p(path);
  const std::filesystem::path dir = p.parent_path().empty() ? "." : p.parent_path();
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) {
    throw InputError(path, 0, flag, "its directory does not exist");
  }
  if (std::filesystem::is_directory(p, ec)) throw InputError(path, 0, flag, "is a directory");
}

void EnsureOutputDirectory(const std::string& dir, const std::string& flag) {
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec)) {
    throw InputError(dir, 0, flag, "exists and is not a directory");
  }
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(dir, 0, flag, "cannot create the directory: " + ec.message());
}

}  // namespace lookout::app
