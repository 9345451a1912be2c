#include "lookout/app/grid_recording.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace lookout::app {
namespace {

std::uint8_t UnitByte(double x) {
  return static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(x, 0.0, 1.0)));
}

}  // namespace

std::uint8_t DirectionByte(double vx_mps, double vy_mps) {
  if (vx_mps == 0.0 && vy_mps == 0.0) return 0;
  // [-pi, pi] -> [0, 256); +pi (exactly along -x) wraps to 0 with -pi.
  const double turn = (std::atan2(vy_mps, vx_mps) + std::numbers::pi) / (2.0 * std::numbers::pi);
  return static_cast<std::uint8_t>(static_cast<int>(std::floor(256.0 * turn)) % 256);
}

std::vector<io::GridLayer8> GridLayersToRecord(const grid::ExtendedGrid& grid) {
  const grid::GridLayers& layers = grid.layers();
  const grid::FilterLayerIds& ids = grid.ids();
  const std::vector<float> o = layers.CopyInWindowOrder(ids.occupancy);
  const std::vector<float> vx = layers.CopyInWindowOrder(ids.velocity_x_mps);
  const std::vector<float> vy = layers.CopyInWindowOrder(ids.velocity_y_mps);
  const std::vector<float> conf = layers.CopyInWindowOrder(ids.velocity_confidence);
  std::array<std::vector<float>, grid::kGridClassCount> pmf;
  for (std::size_t c = 0; c < pmf.size(); ++c) pmf[c] = layers.CopyInWindowOrder(ids.class_pmf[c]);
  std::array<std::vector<float>, grid::kNeighbourCount> links;
  for (std::size_t d = 0; d < links.size(); ++d) {
    links[d] = layers.CopyInWindowOrder(ids.rigidity[d]);
  }

  const std::size_t n = o.size();
  std::vector<io::GridLayer8> out = {{"occupancy", {}},  {"speed", {}}, {"direction", {}},
                                     {"confidence", {}}, {"class", {}}, {"class_probability", {}},
                                     {"rigidity", {}},   {"hidden", {}}};
  for (io::GridLayer8& layer : out) layer.values.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = static_cast<double>(vx[i]);
    const double y = static_cast<double>(vy[i]);
    out[0].values[i] = UnitByte(static_cast<double>(o[i]));
    out[1].values[i] = UnitByte(std::hypot(x, y) / kRecordedFullSpeed_mps);
    out[2].values[i] = DirectionByte(x, y);
    out[3].values[i] = UnitByte(static_cast<double>(conf[i]));
    std::size_t best = 0;
    for (std::size_t c = 1; c < pmf.size(); ++c) {
      if (pmf[c][i] > pmf[best][i]) best = c;
    }
    out[4].values[i] = static_cast<std::uint8_t>(best);
    out[5].values[i] = UnitByte(static_cast<double>(pmf[best][i]));
    float strongest = 0.0f;
    for (const std::vector<float>& l : links) strongest = std::max(strongest, l[i]);
    out[6].values[i] = UnitByte(static_cast<double>(strongest));
  }
  const std::vector<std::uint8_t> hidden =
      grid::HiddenBodyMask(grid.hidden_bodies(), grid.geometry());
  for (std::size_t i = 0; i < n; ++i) out[7].values[i] = hidden[i] != 0 ? 255 : 0;
  return out;
}

}  // namespace lookout::app
