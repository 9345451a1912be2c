#include "lookout/eval/grid_class_metrics.h"

#include <map>

namespace lookout::eval {

void ClassAccuracyAccumulator::AddFrame(std::span<const float> occupancy,
                                        std::span<const std::uint8_t> most_likely,
                                        const sim::TruthRaster& raster,
                                        std::span<const sim::ActorTruth> actors) {
  std::map<int, int> class_of;
  for (const sim::ActorTruth& a : actors) {
    class_of[a.index] = grid_class_of_[static_cast<std::size_t>(a.object_class)];
  }
  for (std::size_t i = 0; i < raster.owner.size(); ++i) {
    const auto it = class_of.find(raster.owner[i]);
    if (it == class_of.end()) continue;  // static world, free, or not an actor of this frame
    if (!(static_cast<double>(occupancy[i]) > occupied_probability_)) continue;
    ++cells_;
    if (static_cast<int>(most_likely[i]) == it->second) ++correct_;
  }
}

std::optional<double> ClassAccuracyAccumulator::Value() const {
  if (cells_ == 0) return std::nullopt;
  return static_cast<double>(correct_) / static_cast<double>(cells_);
}

}  // namespace lookout::eval
