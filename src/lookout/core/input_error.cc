#include "lookout/core/input_error.h"

#include <fmt/format.h>

namespace lookout {
namespace {

std::string Compose(const std::string& file, int line, const std::string& field,
                    const std::string& problem) {
  std::string where = file;
  if (line > 0) where += fmt::format(":{}", line);
  if (!field.empty()) return fmt::format("{}: {}: {}", where, field, problem);
  return fmt::format("{}: {}", where, problem);
}

}  // namespace

InputError::InputError(std::string file, int line, std::string field, const std::string& problem)
    : std::runtime_error(Compose(file, line, field, problem)),
      file_(std::move(file)),
      line_(line),
      field_(std::move(field)),
      problem_(problem) {}

}  // namespace lookout
