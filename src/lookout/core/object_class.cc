#include "lookout/core/object_class.h"

namespace lookout {

std::string_view ToString(ObjectClass c) {
  switch (c) {
    case ObjectClass::kUnknown: return "unknown";
    case ObjectClass::kPedestrian: return "pedestrian";
    case ObjectClass::kCyclist: return "cyclist";
    case ObjectClass::kCar: return "car";
    case ObjectClass::kTruck: return "truck";
    case ObjectClass::kPole: return "pole";
  }
  return "unknown";
}

std::optional<ObjectClass> ParseObjectClass(std::string_view name) {
  for (const ObjectClass c : kAllObjectClasses) {
    if (ToString(c) == name) return c;
  }
  return std::nullopt;
}

}  // namespace lookout
