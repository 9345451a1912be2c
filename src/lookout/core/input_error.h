#pragma once

#include <stdexcept>
#include <string>

namespace lookout {

// An error the user caused: a bad file, option or value. The CLI turns it into exit code 2 and
// one line on stderr, "FILE:LINE: FIELD: what was wrong". Programming errors are assertions,
// never InputError.
class InputError : public std::runtime_error {
 public:
  // `line` is 1-based; 0 when the input has no lines (an option, a binary file).
  InputError(std::string file, int line, std::string field, const std::string& problem);

  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& field() const { return field_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string file_;
  int line_;
  std::string field_;
  std::string problem_;
};

}  // namespace lookout
