#pragma once

// grid.class_accuracy: how often the grid's class layer names the class of what is really
// there. Over the cells truly occupied by an actor (sim::RasteriseTruth) that the grid believes
// occupied (O > occupied_probability, the contract's 0.5), the share whose most probable grid
// class is the actor's: pedestrian, cyclist; car and truck -> vehicle; pole -> static;
// unknown -> unknown (the camera's classes as the grid holds them). Pooled over every cell of
// every frame. The static world is left out: it is most of the grid, and neither the camera nor
// this evidence speaks of walls. Which grid class stands for which object class is the
// caller's (app/stereo_class_evidence.h holds the mapping): this file knows no grid.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "lookout/core/object_class.h"
#include "lookout/sim/truth.h"

namespace lookout::eval {

// For each object class (kAllObjectClasses order), the index of the grid class that stands
// for it.
using GridClassOfObjectClass = std::array<int, kAllObjectClasses.size()>;

class ClassAccuracyAccumulator {
 public:
  explicit ClassAccuracyAccumulator(const GridClassOfObjectClass& grid_class_of,
                                    double occupied_probability = 0.5)
      : grid_class_of_(grid_class_of), occupied_probability_(occupied_probability) {}

  // One frame: per cell in window order, the belief's occupancy and most probable class (a
  // grid class index); the truth rasterised on the same window; the frame's actors (their
  // classes, by ActorTruth::index).
  void AddFrame(std::span<const float> occupancy, std::span<const std::uint8_t> most_likely,
                const sim::TruthRaster& raster, std::span<const sim::ActorTruth> actors);

  std::int64_t cells() const { return cells_; }
  // nullopt before any cell was scored.
  std::optional<double> Value() const;

 private:
  GridClassOfObjectClass grid_class_of_;
  double occupied_probability_;
  std::int64_t cells_ = 0;
  std::int64_t correct_ = 0;
};

}  // namespace lookout::eval
