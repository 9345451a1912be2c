#pragma once

#include <array>
#include <optional>
#include <string_view>

namespace lookout {

// What a thing on the road is. The scenario format knows car, truck, cyclist and pedestrian;
// the stereo sensor of seed 004 also reports pole and unknown.
enum class ObjectClass { kUnknown = 0, kPedestrian, kCyclist, kCar, kTruck, kPole };

inline constexpr std::array<ObjectClass, 6> kAllObjectClasses = {
    ObjectClass::kUnknown, ObjectClass::kPedestrian, ObjectClass::kCyclist,
    ObjectClass::kCar,     ObjectClass::kTruck,      ObjectClass::kPole};

std::string_view ToString(ObjectClass c);
std::optional<ObjectClass> ParseObjectClass(std::string_view name);

}  // namespace lookout
