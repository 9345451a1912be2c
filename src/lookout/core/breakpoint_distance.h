#pragma once

// Borges and Aldon's adaptive breakpoint distance ("Line extraction in 2D range images for
// mobile robotics", J. Intelligent and Robotic Systems 40(3), 2004): two consecutive returns of
// a scanner, dphi apart in bearing, the first at range r, can lie on one surface when they are
// at most
//   D_max = r sin(dphi) / sin(lambda - dphi) + noise
// apart: the distance between neighbouring impacts on a surface seen at the most grazing
// incidence lambda still taken for a surface, plus the range noise (k sigma_r). It grows with
// range as the beams spread. Shared by the lidar segmentation (where a cluster ends) and the
// grid's inverse sensor model (which neighbouring impacts are joined as one surface).

namespace lookout {

// D_max, m. Beams further apart than lambda (dphi >= incidence_rad): no surface rule holds,
// only the noise. Pure.
double BreakpointDistance(double range_m, double dphi_rad, double incidence_rad, double noise_m);

}  // namespace lookout
