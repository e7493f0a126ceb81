#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace merging {

/// As-built against as-planned, per IFC wall (issue 21, docs/deviations.md).
enum class WallStatus { kAsPlanned = 0, kMoved = 1, kNotBuilt = 2, kExtra = 3, kNotSeen = 4 };

/// "AS_PLANNED", "MOVED", "NOT_BUILT", "EXTRA", "NOT_SEEN" (msg/WallDeviation.msg).
const char* ToString(WallStatus status);

/// The tuning of ClassifyWalls; deviation_node's ROS parameters carry the same names
/// (config/deviations.yaml).
struct WallDeviationConfig {
  double planned_offset{0.03};  // m: within this (and planned_angle_deg): AS_PLANNED
  double planned_angle_deg{1.0};
  double max_offset{0.6};         // m: an S-plane farther off is not this wall
  double max_angle_deg{20.0};     // ... nor one turned more
  double min_overlap{0.5};        // m of the A-surface's length an S-plane must cover
  double extra_min_length{1.0};   // m: an unmatched S-plane shorter is clutter, not a wall
  double extra_min_height{1.85};  // m of vertical extent seen (clutter is lower)
  int extra_min_views{2};         // keyframes that observed it: one glimpse is no wall
  double door_margin{0.15};       // m beyond a doorway's half-width: sight lines pass there
  int not_built_min_rays{2};      // sight lines through the wall for NOT_BUILT

  /// "" when valid, else "<parameter>: <what is wrong>".
  std::string Validate() const;
};

/// One IFC wall's status, or an EXTRA S-plane (wall_id -1). Offsets are along the normal of the
/// wall's first surface (surface_a, the simulator's move_wall direction), at the middle of its
/// length; angles anticlockwise about z, from the plan to the build.
struct WallDeviation {
  int wall_id{-1};   // A-Graph wall id; -1 for EXTRA
  std::string guid;  // IFC GlobalId, "" when the IFC had none
  std::string name;
  WallStatus status{WallStatus::kNotSeen};
  double offset{0.0};                              // m
  double angle{0.0};                               // rad
  double sigma{0.0};                               // m: 1-σ of the offset (MOVED / AS_PLANNED)
  std::vector<int> s_planes;                       // the S-plane ids it rests on
  Eigen::Vector2d start{Eigen::Vector2d::Zero()};  // in B: the A-wall's (or EXTRA plane's) extent
  Eigen::Vector2d end{Eigen::Vector2d::Zero()};
  int rays_through{0};  // sight lines / walked steps through where it should stand
  double height{0.0};   // m: EXTRA: the vertical extent seen
  Eigen::Vector2d normal{Eigen::Vector2d::UnitX()};  // the offset's direction (EXTRA: its face's)
};

/// `bim_T_map` corrected by the consensus of the walls seen (a small motion, by robust least
/// squares, that puts the A-surfaces' S-planes back on the plan: the merge can be pulled a few cm
/// by walls built off it). ClassifyWalls and ClassifyDoorways place the S-Graph by this.
Eigen::Isometry3d ConsensusBimTMap(const agraph::AGraph& building, const sgraph::SGraph& graph,
                                   const Eigen::Isometry3d& bim_T_map,
                                   const WallDeviationConfig& config);

/// Classifies every wall of `building` (one storey, as the merger holds it) against the S-Graph
/// `graph` placed in B by `bim_T_map` (the merge's estimate), and lists the wall-height S-planes
/// no A-surface explains as EXTRA. Deterministic; O(walls x planes x sight lines).
std::vector<WallDeviation> ClassifyWalls(const agraph::AGraph& building,
                                         const sgraph::SGraph& graph,
                                         const Eigen::Isometry3d& bim_T_map,
                                         const WallDeviationConfig& config);

}  // namespace merging
}  // namespace is_graphs
