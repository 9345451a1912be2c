#pragma once

// MOTChallenge text files (Milan, Leal-Taixe, Reid, Roth and Schindler, "MOT16: a benchmark
// for multi-object tracking", 2016; and MOT15 before it): one object per line,
//   frame, id, bb_left, bb_top, bb_width, bb_height, conf, x, y, z
// comma-separated, boxes in pixels. Ground truth (gt.txt) and tracker output use the same
// layout. MOT15 writes all ten columns; later files write fewer (MOT16/17 ground truth uses
// columns 8 and 9 for class and visibility), so 6 to 10 columns are read and a missing one is
// -1, the format's "not given". Blank lines are skipped; rows need not be sorted.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace lookout::io {

struct MotChallengeRow {
  std::int64_t frame = 0;  // >= 0 (MOTChallenge counts from 1)
  std::int64_t id = 0;     // any integer; detections without identity write -1
  double bb_left = 0.0;
  double bb_top = 0.0;
  double bb_width = 0.0;   // >= 0
  double bb_height = 0.0;  // >= 0
  double conf = -1.0;
  double x = -1.0;  // world position in MOT15 (class in MOT16/17 ground truth)
  double y = -1.0;  // (visibility in MOT16/17 ground truth)
  double z = -1.0;
  int line = 0;  // 1-based line of the row in its file
};

// Parses `text`; `source` names it in errors. A malformed line throws lookout::InputError with
// the source, the 1-based line and the field (e.g. "bb_width"): a column that is not a finite
// number, a frame or id that is not an integer, a negative size, fewer than 6 or more than 10
// columns.
std::vector<MotChallengeRow> ParseMotChallenge(std::string_view text, const std::string& source);

// Reads and parses a file; a file that cannot be read is an InputError too.
std::vector<MotChallengeRow> ReadMotChallengeFile(const std::string& path);

}  // namespace lookout::io
