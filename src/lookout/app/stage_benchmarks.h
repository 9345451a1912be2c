#pragma once

// The figures of `lookout bench` that time one stage on a fixed input (the issues' benchmark
// set-ups, measured in-process so that the command needs nothing but the binary; the Google
// Benchmark programs in bench/ give the same measurements with their statistics).

#include <cstddef>

#include "lookout/grid/extended_grid.h"
#include "lookout/grid/inverse_sensor_model.h"
#include "lookout/sim/scenario.h"

namespace lookout::app {

struct GridCycleFigures {
  double cycle_ms_median = 0.0;  // ExtendedGrid::Update, the whole cycle
  // Its part the literal reference computes too (the scan pair's preparation, steps 2-7, the
  // clusters' stage: ExtendedGrid::Stats::motion_ms), and the reference's time for the same
  // stages on the same input and scan pair.
  double motion_ms_median = 0.0;
  double reference_ms_median = 0.0;
  double reference_speedup = 0.0;    // reference over the fast path's same stages
  std::size_t sources = 0;           // active cells moved in the timed update
};

// The input of one timed grid update: the grid's state before the scan at the first lidar frame
// at or after `at_s` of `scenario` (the grid having run every earlier scan: a steady state of
// tracked structure, movers and newly revealed occupancy), already scrolled to that scan's
// window, the scan's measurement and its time step. The 400 x 400 grid of 0.15 m cells of
// GridOptions. Throws std::invalid_argument when no lidar frame follows at_s.
struct GridCycleInput {
  grid::ExtendedGrid before;
  grid::MeasurementGrid z;
  double dt_s = 0.0;
};
// `filter`: the grid's filter options (the scan pair's memory, scan_flow.h, comes with the state).
GridCycleInput PrepareGridCycle(const sim::Scenario& scenario, double at_s,
                                const grid::FilterOptions& filter = {});

// One grid update on `scenario`'s scan at the first lidar frame at or after `at_s`, the grid
// having run every earlier scan (a steady state: tracked structure, movers, newly revealed
// occupancy), the 400 x 400 grid of 0.15 m cells. Each repetition updates a fresh copy of the
// same state with the same measurement; copying is not timed. The reference's repetitions run
// spread among the fast path's (side by side in time).
GridCycleFigures MeasureGridCycle(const sim::Scenario& scenario, double at_s, int repetitions,
                                  int reference_repetitions);

// One risk step: the ego and `tracks` seeded road users round a junction, 5 s horizon, `samples`
// Monte Carlo samples each; the median over `repetitions`, ms.
double MeasureRiskStepMs(int tracks, int samples, int repetitions);

// One MHT step (m = hypotheses_m global hypotheses, N = n_scan) on the tracking benchmark scene
// (tracking/benchmark_scene.h: `targets` road users and `false_objects` false detections a
// scan, 10 Hz), timed on the scan after 2 s of tracking; each repetition steps a fresh copy of
// the same tracker state, copying not timed. The median over `repetitions`, ms.
double MeasureMhtStepMs(int targets, int false_objects, int hypotheses_m, int n_scan,
                        int repetitions);

}  // namespace lookout::app
