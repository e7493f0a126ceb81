#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/common/result.h"
#include "is_graphs/geometry/triangle_mesh.h"
#include "is_graphs/merging/wall_deviations.h"

namespace is_graphs {
namespace navigation {

/// How a storey of the BIM becomes a navigation map (docs/navigation.md); agraph_node's `map_*`
/// parameters and the bim_map tool's options carry the same names.
struct GridConfig {
  double resolution{0.05};         // m per cell
  double slice_min{0.1};           // m above the storey's elevation: the robot's height band, whose
  double slice_max{1.0};           //   wall, column (any element's) sections are occupied
  double margin{1.0};              // m of unknown around the storey's walls and rooms
  double door_default_width{0.9};  // m, for a doorway the IFC gives no width
  double extra_thickness{0.1};     // m, an EXTRA wall's (as built)

  /// "" when valid, else "<field>: <what is wrong>".
  std::string Validate() const;
};

/// A row-major grid in B, row 0 at origin.y(): map_server's cell values.
struct OccupancyGrid {
  static constexpr std::int8_t kUnknown = -1;
  static constexpr std::int8_t kFree = 0;
  static constexpr std::int8_t kOccupied = 100;

  double resolution{0.05};
  Eigen::Vector2d origin{Eigen::Vector2d::Zero()};  // the lower-left corner of cell (0, 0)
  double elevation{0.0};                            // the storey's, m (the map's z in B)
  int width{0};
  int height{0};
  std::vector<std::int8_t> cells;

  bool Contains(int ix, int iy) const { return ix >= 0 && iy >= 0 && ix < width && iy < height; }
  std::int8_t At(int ix, int iy) const { return cells[static_cast<size_t>(iy) * width + ix]; }
  std::int8_t& At(int ix, int iy) { return cells[static_cast<size_t>(iy) * width + ix]; }
  /// The cell holding `p` (may lie outside the grid: check Contains).
  Eigen::Vector2i CellOf(const Eigen::Vector2d& p) const;
  Eigen::Vector2d CentreOf(int ix, int iy) const;
  /// Whether an occupied cell lies within `cells` cells (Chebyshev) of the one holding `p`.
  bool OccupiedNear(const Eigen::Vector2d& p, int cells) const;
};

/// The navigation map of one storey: `storey_graph` holds one storey (agraph::SelectStorey).
/// Unknown everywhere, the rooms free, then occupied: every wall's footprint and faces whose
/// height overlaps the slice band, and, with a mesh, every element's section in that band (not
/// doors, furniture, coverings, the site: docs/navigation.md); last, each doorway through a wall
/// freed across the wall (its width). `deviations` (optional, the `deviations` topic's walls,
/// matched to the storey's walls by IFC GlobalId and position): NOT_BUILT walls freed, MOVED walls
/// drawn where they were built (the plan's place freed), EXTRA walls added.
Result<OccupancyGrid> BuildStoreyGrid(
    const agraph::AGraph& storey_graph, const geometry::TriangleMesh* mesh,
    const GridConfig& config, const std::vector<merging::WallDeviation>* deviations = nullptr);

/// The footprint of a wall in B (four corners, from its two faces).
std::vector<Eigen::Vector2d> WallFootprint(const agraph::AGraph& graph, const agraph::Wall& wall);

/// Counts of free, occupied and unknown cells (in that order).
Eigen::Vector3i CountCells(const OccupancyGrid& grid);

}  // namespace navigation
}  // namespace is_graphs
