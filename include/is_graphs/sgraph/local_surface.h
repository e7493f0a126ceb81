#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "is_graphs/sgraph/point_types.h"

namespace is_graphs {
namespace sgraph {

/// The shape of the cloud around each point: whether a RANSAC inlier lies on that plane or only
/// passes within its distance band, such as a perpendicular wall at a corner or a door's reveal.
///
/// The points are hashed into cubic cells; a point's surroundings are its cell and the 26 around
/// it (a cube of 3 cells a side), whose point moments give their principal axes. Computed once
/// per occupied cell, on demand.
class LocalSurfaces {
 public:
  LocalSurfaces(const PointList& points, double cell_size);

  /// The indices whose surroundings agree with a plane of normal `normal` (unit): where they
  /// are planar, their normal within `max_angle_rad` of it; where they are a line (one scan
  /// ring), the line within `max_angle_rad` of the plane. Too few points around: kept.
  std::vector<int> OnPlane(const std::vector<int>& indices, const Eigen::Vector3d& normal,
                           double max_angle_rad);

 private:
  struct Moments {
    int count{0};
    Eigen::Vector3d sum{Eigen::Vector3d::Zero()};
    Eigen::Matrix3d outer{Eigen::Matrix3d::Zero()};  // Σ p pᵀ
  };
  struct Shape {
    bool computed{false};
    bool known{false};
    bool linear{false};
    Eigen::Vector3d axis{Eigen::Vector3d::Zero()};  // the normal, or the line's direction
  };
  struct Cell {
    Moments moments;
    Shape shape;
    Eigen::Vector3i index{Eigen::Vector3i::Zero()};
  };
  const Shape& ShapeOf(Cell& cell);

  std::unordered_map<std::uint64_t, Cell> cells_;
  std::vector<Cell*> cell_of_point_;
};

}  // namespace sgraph
}  // namespace is_graphs
