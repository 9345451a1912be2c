#include "lookout/eval/trajectory_io.h"

#include <fmt/format.h>

#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <system_error>

#include "lookout/core/input_error.h"

namespace lookout::eval {
namespace {

// Splits `text` into its non-comment lines and reads each as exactly N finite numbers named by
// `fields`, calling `on_line` with them.
template <std::size_t N, typename OnLine>
void ParseNumberLines(std::string_view text, const std::string& name,
                      const std::array<const char*, N>& fields, OnLine on_line) {
  int line_number = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_number;
    const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
    std::size_t i = 0;
    while (i < line.size() && blank(line[i])) ++i;
    if (i == line.size() || line[i] == '#') continue;

    std::array<double, N> values{};
    for (std::size_t k = 0; k < N; ++k) {
      while (i < line.size() && blank(line[i])) ++i;
      const std::size_t start = i;
      while (i < line.size() && !blank(line[i])) ++i;
      if (start == i) throw InputError(name, line_number, fields[k], "missing");
      const std::string_view token = line.substr(start, i - start);
      const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), values[k]);
      if (ec != std::errc() || ptr != token.data() + token.size()) {
        throw InputError(name, line_number, fields[k], fmt::format("not a number: '{}'", token));
      }
      if (!std::isfinite(values[k])) {
        throw InputError(name, line_number, fields[k], "not a finite number");
      }
    }
    while (i < line.size() && blank(line[i])) ++i;
    if (i < line.size()) {
      throw InputError(name, line_number, "", fmt::format("more than the {} fields of a line", N));
    }
    on_line(values);
  }
}

std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw InputError(path.string(), 0, "", "cannot open the file");
  const std::streamoff size = in.tellg();
  if (size < 0) throw InputError(path.string(), 0, "", "cannot read: not a regular file");
  std::string text(static_cast<std::size_t>(size), '\0');
  in.seekg(0);
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (!in) throw InputError(path.string(), 0, "", "cannot read the file");
  return text;
}

void WriteText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();
  if (!out) throw std::runtime_error(fmt::format("cannot write {}", path.string()));
}

}  // namespace

std::string FormatTrajectory(const Trajectory2& trajectory) {
  std::string text;
  for (const StampedPose2& p : trajectory) {
    // fmt's {} is the shortest representation that reads back exactly.
    text += fmt::format("{} {} {} {}\n", p.t_s, p.pose.x(), p.pose.y(), p.pose.yaw);
  }
  return text;
}

Trajectory2 ParseTrajectory(std::string_view text, const std::string& name) {
  Trajectory2 trajectory;
  ParseNumberLines<4>(text, name, {"t", "x", "y", "theta"}, [&](const std::array<double, 4>& v) {
    // The heading as written, not wrapped: a reader must give back what was written.
    StampedPose2 p;
    p.t_s = v[0];
    p.pose.translation = Eigen::Vector2d(v[1], v[2]);
    p.pose.yaw = v[3];
    trajectory.push_back(p);
  });
  return trajectory;
}

void WriteTrajectory(const std::filesystem::path& path, const Trajectory2& trajectory) {
  WriteText(path, FormatTrajectory(trajectory));
}

Trajectory2 ReadTrajectory(const std::filesystem::path& path) {
  return ParseTrajectory(ReadText(path), path.string());
}

std::string FormatRelations(const std::vector<Relation2>& relations) {
  std::string text;
  for (const Relation2& r : relations) {
    text += fmt::format("{} {} {} {} 0 0 0 {}\n", r.t1_s, r.t2_s, r.motion.x(), r.motion.y(),
                        r.motion.yaw);
  }
  return text;
}

std::vector<Relation2> ParseRelations(std::string_view text, const std::string& name) {
  std::vector<Relation2> relations;
  ParseNumberLines<8>(text, name, {"t1", "t2", "x", "y", "z", "roll", "pitch", "yaw"},
                      [&](const std::array<double, 8>& v) {
                        Relation2 r;
                        r.t1_s = v[0];
                        r.t2_s = v[1];
                        r.motion.translation = Eigen::Vector2d(v[2], v[3]);
                        r.motion.yaw = v[7];
                        relations.push_back(r);
                      });
  return relations;
}

void WriteRelations(const std::filesystem::path& path, const std::vector<Relation2>& relations) {
  WriteText(path, FormatRelations(relations));
}

std::vector<Relation2> ReadRelations(const std::filesystem::path& path) {
  return ParseRelations(ReadText(path), path.string());
}

}  // namespace lookout::eval
