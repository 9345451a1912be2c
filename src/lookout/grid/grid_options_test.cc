#include "lookout/grid/grid_options.h"

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>

#include "lookout/core/input_error.h"

namespace lookout::grid {
namespace {

// The field path of the InputError `change` provokes, or "" when it validates.
std::string FailingField(const std::function<void(GridOptions&)>& change) {
  GridOptions o;
  change(o);
  try {
    o.Validate("test.yaml");
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "test.yaml");
    EXPECT_EQ(e.line(), 0);
    return e.field();
  }
  return "";
}

TEST(GridOptionsTest, DefaultsAreValid) {
  EXPECT_EQ(FailingField([](GridOptions&) {}), "");
}

TEST(GridOptionsTest, NamesTheFieldOutOfRange) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(FailingField([](GridOptions& o) { o.cell_size_m = 0.0; }), "grid.cell_size_m");
  EXPECT_EQ(FailingField([&](GridOptions& o) { o.cell_size_m = nan; }), "grid.cell_size_m");
  EXPECT_EQ(FailingField([](GridOptions& o) { o.width_cells = 0; }), "grid.width_cells");
  EXPECT_EQ(FailingField([](GridOptions& o) { o.height_cells = 100000; }), "grid.height_cells");

  const std::string ism = "grid.inverse_sensor_model.";
  auto& field = FailingField;
  EXPECT_EQ(field([](GridOptions& o) { o.inverse_sensor_model.p_hit = 1.0; }), ism + "p_hit");
  EXPECT_EQ(field([](GridOptions& o) { o.inverse_sensor_model.p_hit = 0.5; }), ism + "p_hit");
  EXPECT_EQ(field([&](GridOptions& o) { o.inverse_sensor_model.p_hit = nan; }), ism + "p_hit");
  EXPECT_EQ(field([](GridOptions& o) { o.inverse_sensor_model.p_free = 0.0; }), ism + "p_free");
  EXPECT_EQ(field([](GridOptions& o) { o.inverse_sensor_model.p_free = 0.5; }), ism + "p_free");
  // A no-return beam may not be stronger free evidence than a return.
  EXPECT_EQ(field([](GridOptions& o) { o.inverse_sensor_model.p_free_no_return = 0.2; }),
            ism + "p_free_no_return");
  EXPECT_EQ(field([](GridOptions& o) { o.inverse_sensor_model.p_free_no_return = 0.5; }),
            ism + "p_free_no_return");
  EXPECT_EQ(field([](GridOptions& o) { o.inverse_sensor_model.no_return_free_range_m = -1.0; }),
            ism + "no_return_free_range_m");
  EXPECT_EQ(field([](GridOptions& o) {
              o.inverse_sensor_model.no_return_free_range_m =
                  std::numeric_limits<double>::infinity();
            }),
            ism + "no_return_free_range_m");
  // The boundary cases that are allowed.
  EXPECT_EQ(field([](GridOptions& o) {
              o.inverse_sensor_model.p_free_no_return = o.inverse_sensor_model.p_free;
              o.inverse_sensor_model.no_return_free_range_m = 0.0;
            }),
            "");
}

}  // namespace
}  // namespace lookout::grid
