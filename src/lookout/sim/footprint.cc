#include "lookout/sim/footprint.h"

namespace lookout::sim {

Footprint Footprint::ForActor(const ActorSpec& actor) {
  if (actor.object_class == ObjectClass::kPedestrian) return Circle(actor.radius_m);
  return Box(actor.length_m > 0.0 ? actor.length_m : DefaultLength(actor.object_class),
             actor.width_m > 0.0 ? actor.width_m : DefaultWidth(actor.object_class));
}

Shape FootprintAt(const Footprint& footprint, const Pose2& pose, int owner) {
  if (footprint.kind == Footprint::Kind::kCircle) {
    return Shape::Circle(pose.translation, footprint.radius_m, owner);
  }
  return Shape::Box(pose, footprint.length_m, footprint.width_m, owner);
}

}  // namespace lookout::sim
