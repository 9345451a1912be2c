#pragma once

// The typical footprint of each road user's class: the scenario format's defaults
// (docs/scenarios.md), which the simulator gives an actor without a size of its own, and which
// every stage that must guess a body from its class uses (the tracking stage's depth behind a
// seen side, fusion's hidden extent, the risk stage's boxes, a scan's view of a track). One table,
// so that they cannot drift apart.

#include <optional>

#include "lookout/core/object_class.h"

namespace lookout {

struct ClassFootprints {
  double pedestrian_radius_m = 0.3;
  double cyclist_length_m = 1.8, cyclist_width_m = 0.6;  // a bicycle with its rider
  double car_length_m = 4.5, car_width_m = 1.8;          // a mid-size car
  double truck_length_m = 8.0, truck_width_m = 2.5;      // a rigid two-axle truck

  struct Box {
    double length_m = 0.0;
    double width_m = 0.0;
  };
  // The box of class c: a walker's is the square about its circle; unknown objects and poles
  // take a car's (the simulator's rule).
  Box BoxOf(ObjectClass c) const {
    switch (c) {
      case ObjectClass::kPedestrian:
        return {2.0 * pedestrian_radius_m, 2.0 * pedestrian_radius_m};
      case ObjectClass::kCyclist:
        return {cyclist_length_m, cyclist_width_m};
      case ObjectClass::kTruck:
        return {truck_length_m, truck_width_m};
      default:
        return {car_length_m, car_width_m};
    }
  }

  // The first field that is not finite and > 0 (its name, as "car_width_m"), if any: each
  // stage reports it in its own options' error.
  std::optional<const char*> FirstInvalidField() const;
};

}  // namespace lookout
