#include "lookout/io/mot_challenge.h"

#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "lookout/core/input_error.h"

namespace lookout::io {
namespace {

constexpr std::array<const char*, 10> kFieldNames = {
    "frame", "id", "bb_left", "bb_top", "bb_width", "bb_height", "conf", "x", "y", "z"};
constexpr std::size_t kMinColumns = 6;

// Integers beyond 2^53 are not exact in a double, and MOTChallenge writes integers in any
// notation ("12", "12.0"), so frame and id are parsed as doubles and must be whole and
// within this range.
constexpr double kMaxExactInteger = 9007199254740992.0;

std::string_view Trim(std::string_view s) {
  const auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

double ParseNumber(std::string_view text, const std::string& source, int line, const char* field) {
  const std::string_view t = Trim(text);
  if (t.empty()) throw InputError(source, line, field, "empty column");
  double value = 0.0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  if (ec == std::errc::result_out_of_range) {
    throw InputError(source, line, field, "number out of range: '" + std::string(t) + "'");
  }
  if (ec != std::errc() || end != t.data() + t.size()) {
    throw InputError(source, line, field, "not a number: '" + std::string(t) + "'");
  }
  if (!std::isfinite(value)) {
    throw InputError(source, line, field, "not a finite number: '" + std::string(t) + "'");
  }
  return value;
}

std::int64_t ParseInteger(std::string_view text, const std::string& source, int line,
                          const char* field) {
  const double value = ParseNumber(text, source, line, field);
  if (value != std::floor(value) || std::fabs(value) > kMaxExactInteger) {
    throw InputError(source, line, field, "not an integer: '" + std::string(Trim(text)) + "'");
  }
  return static_cast<std::int64_t>(value);
}

MotChallengeRow ParseRow(std::string_view text, const std::string& source, int line) {
  std::array<std::string_view, kFieldNames.size()> columns;
  std::size_t count = 0;
  while (true) {
    const std::size_t comma = text.find(',');
    if (count == columns.size()) {
      throw InputError(source, line, "z", "more than 10 columns");
    }
    columns[count++] = text.substr(0, comma);
    if (comma == std::string_view::npos) break;
    text.remove_prefix(comma + 1);
  }
  if (count < kMinColumns) {
    throw InputError(source, line, kFieldNames[count],
                     "missing: a row has at least 6 columns (frame, id, bb_left, bb_top, "
                     "bb_width, bb_height), found " +
                         std::to_string(count));
  }
  MotChallengeRow row;
  row.line = line;
  row.frame = ParseInteger(columns[0], source, line, kFieldNames[0]);
  if (row.frame < 0) throw InputError(source, line, kFieldNames[0], "negative frame number");
  row.id = ParseInteger(columns[1], source, line, kFieldNames[1]);
  std::array<double*, 8> values = {&row.bb_left, &row.bb_top, &row.bb_width, &row.bb_height,
                                   &row.conf,    &row.x,      &row.y,        &row.z};
  for (std::size_t k = 2; k < count; ++k) {
    *values[k - 2] = ParseNumber(columns[k], source, line, kFieldNames[k]);
  }
  if (row.bb_width < 0.0) throw InputError(source, line, "bb_width", "negative box width");
  if (row.bb_height < 0.0) throw InputError(source, line, "bb_height", "negative box height");
  return row;
}

}  // namespace

std::vector<MotChallengeRow> ParseMotChallenge(std::string_view text, const std::string& source) {
  std::vector<MotChallengeRow> rows;
  int line = 0;
  while (!text.empty()) {
    ++line;
    const std::size_t newline = text.find('\n');
    const std::string_view content = text.substr(0, newline);
    text.remove_prefix(newline == std::string_view::npos ? text.size() : newline + 1);
    if (Trim(content).empty()) continue;
    rows.push_back(ParseRow(content, source, line));
  }
  return rows;
}

std::vector<MotChallengeRow> ReadMotChallengeFile(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(path, 0, "", "cannot open: it is a directory");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", "cannot open the file for reading");
  std::ostringstream content;
  content << in.rdbuf();
  if (in.bad()) throw InputError(path, 0, "", "cannot read the file");
  return ParseMotChallenge(content.str(), path);
}

}  // namespace lookout::io
