#pragma once

// Text files of trajectories and relations, for `lookout slam` and the tools that score it.
//
// Trajectory (docs/cli-contract.md, `lookout slam --trajectory`): one pose a line,
//   t x y theta
// t in seconds in the log's own time base, x and y in metres, theta in radians. Written with the
// shortest decimal that reads back to the same double, so a file read back gives the same poses
// bit for bit and the same input always gives the same bytes.
//
// Relations (Kuemmerle et al. 2009, as their published .relations files): one a line,
//   t1 t2 x y z roll pitch yaw
// the motion from the pose at t1 to the pose at t2 in the frame of the first; z, roll and pitch
// are read (they must be numbers) and ignored in the plane, and written as 0.
//
// Readers skip blank lines and lines starting with '#'; any other line must hold exactly the
// fields above, each a finite number, or the file is refused with an InputError naming the
// file, the 1-based line and the field. Neither reader requires the times to increase: the
// error functions check that where it matters (trajectory_error.h).

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "lookout/eval/relation_error.h"
#include "lookout/eval/trajectory_error.h"

namespace lookout::eval {

std::string FormatTrajectory(const Trajectory2& trajectory);
Trajectory2 ParseTrajectory(std::string_view text, const std::string& name);

// Throws std::runtime_error when the file cannot be written.
void WriteTrajectory(const std::filesystem::path& path, const Trajectory2& trajectory);
Trajectory2 ReadTrajectory(const std::filesystem::path& path);

std::string FormatRelations(const std::vector<Relation2>& relations);
std::vector<Relation2> ParseRelations(std::string_view text, const std::string& name);

void WriteRelations(const std::filesystem::path& path, const std::vector<Relation2>& relations);
std::vector<Relation2> ReadRelations(const std::filesystem::path& path);

}  // namespace lookout::eval
