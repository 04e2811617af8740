#include "rover/apl/mobility/mobility_types.hpp"

namespace rover::apl::mobility {

bool ModeHasGoal(Mode m) {
  switch (m) {
    case Mode::kGoToWaypoint:
    case Mode::kVisOdomGoToWaypoint:
    case Mode::kAutoNav:
    case Mode::kAutoNavVisOdom:
    case Mode::kLongTraverse:
      return true;
    default:
      return false;
  }
}

bool ModeHasPrimitives(Mode m) {
  switch (m) {
    case Mode::kDirected:
    case Mode::kVisOdom:
    case Mode::kGuarded:
    case Mode::kGuardedVisOdom:
    case Mode::kGuardedArc:
      return true;
    default:
      return false;
  }
}

bool ModeUsesVisOdom(Mode m) {
  return m == Mode::kVisOdom || m == Mode::kVisOdomGoToWaypoint || m == Mode::kGuardedVisOdom ||
         m == Mode::kAutoNavVisOdom;
}

}  // namespace rover::apl::mobility
