#pragma once
// Drawing into an OccupancyGrid: polygons (by cell centre), segments (every cell they cross),
// and triangles' sections within a height band.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "is_graphs/navigation/occupancy_grid.h"

namespace is_graphs {
namespace navigation {

class GridRaster {
 public:
  explicit GridRaster(OccupancyGrid& grid) : grid_(grid) {}

  /// Every cell whose centre lies inside `polygon` (even-odd rule; any orientation).
  void FillPolygon(const std::vector<Eigen::Vector2d>& polygon, std::int8_t value);
  /// Every cell the segment passes through (sampled at a quarter cell).
  void MarkSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, std::int8_t value);
  /// The part of the triangle with z in [z0, z1], seen from above: its outline and inside.
  void FillSection(const std::array<Eigen::Vector3d, 3>& triangle, double z0, double z1,
                   std::int8_t value);

 private:
  void Set(const Eigen::Vector2i& c, std::int8_t value) {
    if (grid_.Contains(c.x(), c.y())) grid_.At(c.x(), c.y()) = value;
  }
  OccupancyGrid& grid_;
};

}  // namespace navigation
}  // namespace is_graphs
