#include "is_graphs/agraph/agraph.h"

namespace is_graphs {
namespace agraph {

Eigen::Vector3d WallSurface::Tangent() const {
  // ẑ × n = (−n_y, n_x, 0); a horizontal surface has no horizontal tangent: x̂ then.
  const Eigen::Vector3d t(-plane.normal.y(), plane.normal.x(), 0.0);
  const double norm = t.norm();
  return norm > 1e-12 ? Eigen::Vector3d(t / norm) : Eigen::Vector3d::UnitX();
}

const char* ToString(DoorwayKind kind) {
  switch (kind) {
    case DoorwayKind::kOpening:
      return "opening";
    case DoorwayKind::kVirtual:
      return "virtual";
    case DoorwayKind::kDoor:
      break;
  }
  return "door";
}

}  // namespace agraph
}  // namespace is_graphs
