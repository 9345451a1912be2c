#include "lookout/io/grid_images.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <string>

namespace lookout::io {
namespace {

std::size_t CheckedCellCount(const GridGeometry& geometry) {
  if (geometry.width <= 0 || geometry.height <= 0) {
    throw std::invalid_argument("grid image: empty geometry");
  }
  return static_cast<std::size_t>(geometry.width) * static_cast<std::size_t>(geometry.height);
}

void CheckLayer(std::span<const float> layer, std::size_t cells, const char* name, bool optional) {
  if ((optional && layer.empty()) || layer.size() == cells) return;
  throw std::invalid_argument(std::string("grid image: layer ") + name + " holds " +
                              std::to_string(layer.size()) + " values, the geometry " +
                              std::to_string(cells));
}

// The window-order index of the cell drawn at image pixel (x, y): row 0 is the top, north.
std::size_t CellOfPixel(const GridGeometry& geometry, int x, int y) {
  return static_cast<std::size_t>(geometry.height - 1 - y) *
             static_cast<std::size_t>(geometry.width) +
         static_cast<std::size_t>(x);
}

std::uint8_t ToByte(double unit) {
  return static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(unit, 0.0, 1.0)));
}

// Calls draw(pixel_offset, cell_index) for every pixel of an image of the geometry's size.
template <typename Draw>
Image8 Render(const GridGeometry& geometry, PixelFormat format, Draw draw) {
  Image8 image = Image8::Filled(geometry.width, geometry.height, format);
  for (int y = 0; y < geometry.height; ++y) {
    for (int x = 0; x < geometry.width; ++x) {
      draw(image.Offset(x, y), CellOfPixel(geometry, x, y), image);
    }
  }
  return image;
}

}  // namespace

Image8 RenderOccupancy(const GridGeometry& geometry, std::span<const float> occupancy) {
  CheckLayer(occupancy, CheckedCellCount(geometry), "occupancy", false);
  return Render(geometry, PixelFormat::kGray8,
                [&](std::size_t pixel, std::size_t cell, Image8& image) {
                  double o = static_cast<double>(occupancy[cell]);
                  if (std::isnan(o)) o = 0.5;
                  image.pixels[pixel] = ToByte(1.0 - o);
                });
}

std::array<std::uint8_t, 3> SpeedColor(double velocity_x_mps, double velocity_y_mps, double value) {
  if (!std::isfinite(velocity_x_mps) || !std::isfinite(velocity_y_mps) || !(value > 0.0)) {
    return {0, 0, 0};
  }
  double hue_deg = std::atan2(velocity_y_mps, velocity_x_mps) * 180.0 / std::numbers::pi;
  if (hue_deg < 0.0) hue_deg += 360.0;
  if (hue_deg >= 360.0) hue_deg = 0.0;
  // HSV to RGB with saturation 1.
  const double v = std::min(value, 1.0);
  const double h = hue_deg / 60.0;
  const double ramp = v * (1.0 - std::abs(std::fmod(h, 2.0) - 1.0));
  // Per 60-degree sector: the channel at full value v and the one ramping between 0 and v (the
  // third is 0).
  static constexpr std::array<std::array<std::size_t, 2>, 6> kFullAndRamp = {
      {{0, 1}, {1, 0}, {1, 2}, {2, 1}, {2, 0}, {0, 2}}};
  const std::size_t sector = std::min(static_cast<std::size_t>(h), std::size_t{5});
  std::array<double, 3> rgb = {0.0, 0.0, 0.0};
  rgb[kFullAndRamp[sector][0]] = v;
  rgb[kFullAndRamp[sector][1]] = ramp;
  return {ToByte(rgb[0]), ToByte(rgb[1]), ToByte(rgb[2])};
}

Image8 RenderSpeedMap(const GridGeometry& geometry, std::span<const float> velocity_x_mps,
                      std::span<const float> velocity_y_mps, std::span<const float> occupancy,
                      std::span<const float> velocity_confidence, const SpeedMapOptions& options) {
  const std::size_t cells = CheckedCellCount(geometry);
  CheckLayer(velocity_x_mps, cells, "velocity_x_mps", false);
  CheckLayer(velocity_y_mps, cells, "velocity_y_mps", false);
  CheckLayer(occupancy, cells, "occupancy", true);
  CheckLayer(velocity_confidence, cells, "velocity_confidence", true);
  if (!(options.max_speed_mps > 0.0)) {
    throw std::invalid_argument("SpeedMapOptions.max_speed_mps: must be > 0");
  }
  const bool by_occupancy = options.weight_by_occupancy && !occupancy.empty();
  const bool by_confidence = options.weight_by_confidence && !velocity_confidence.empty();
  return Render(geometry, PixelFormat::kRgb8,
                [&](std::size_t pixel, std::size_t cell, Image8& image) {
                  const double vx = static_cast<double>(velocity_x_mps[cell]);
                  const double vy = static_cast<double>(velocity_y_mps[cell]);
                  double value = std::min(std::hypot(vx, vy) / options.max_speed_mps, 1.0);
                  if (by_occupancy) {
                    value *= std::max(0.0, 2.0 * static_cast<double>(occupancy[cell]) - 1.0);
                  }
                  if (by_confidence) {
                    value *= std::clamp(static_cast<double>(velocity_confidence[cell]), 0.0, 1.0);
                  }
                  const std::array<std::uint8_t, 3> rgb = SpeedColor(vx, vy, value);
                  std::copy(rgb.begin(), rgb.end(),
                            image.pixels.begin() + static_cast<std::ptrdiff_t>(pixel));
                });
}

Image8 RenderClassMap(const GridGeometry& geometry, std::span<const std::uint8_t> class_index,
                      std::span<const float> occupancy) {
  const std::size_t cells = CheckedCellCount(geometry);
  if (class_index.size() != cells) {
    throw std::invalid_argument("grid image: class_index holds " +
                                std::to_string(class_index.size()) + " values, the geometry " +
                                std::to_string(cells));
  }
  CheckLayer(occupancy, cells, "occupancy", true);
  return Render(
      geometry, PixelFormat::kRgb8, [&](std::size_t pixel, std::size_t cell, Image8& image) {
        const std::uint8_t c = class_index[cell];
        const bool empty = !occupancy.empty() && !(static_cast<double>(occupancy[cell]) > 0.5);
        const std::array<std::uint8_t, 3>& rgb =
            (empty || c >= kClassPaletteSize) ? kClassBackground : kClassPalette[c];
        std::copy(rgb.begin(), rgb.end(),
                  image.pixels.begin() + static_cast<std::ptrdiff_t>(pixel));
      });
}

}  // namespace lookout::io
