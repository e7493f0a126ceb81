#include "is_graphs/agraph/agraph.h"

namespace is_graphs {
namespace agraph {

Eigen::Vector3d WallSurface::Tangent() const {
  // ẑ × n = (−n_y, n_x, 0); a horizontal surface has no horizontal tangent: x̂ then.
  const Eigen::Vector3d t(-plane.normal.y(), plane.normal.x(), 0.0);
  const double norm = t.norm();
  return norm > 1e-12 ? Eigen::Vector3d(t / norm) : Eigen::Vector3d::UnitX();
}

}  // namespace agraph
}  // namespace is_graphs
