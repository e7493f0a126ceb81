#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/merging/wall_deviations.h"
#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace merging {

/// Whether an IFC door / opening is open as planned or closed (issue 21, docs/deviations.md).
enum class DoorwayStatus { kPresent = 0, kClosed = 1, kNotSeen = 2 };

/// "PRESENT", "CLOSED", "NOT_SEEN" (msg/DoorwayDeviation.msg).
const char* ToString(DoorwayStatus status);

/// The tuning of ClassifyDoorways; deviation_node's parameters carry the same names with a
/// `doorway_` prefix (config/deviations.yaml).
struct DoorwayDeviationConfig {
  double default_width{0.8};       // m: a doorway's width when the A-Graph has none
  double walk_margin{0.3};         // m beyond half the width: an S-doorway there is this one
  double view_distance{5.0};       // m: keyframes farther from the doorway give no evidence on it
  int present_min_rays{2};         // sight lines through the opening for PRESENT (not walked)
  double closed_min_cover{0.7};    // share of the opening's width a covering S-plane spans
  double closed_max_offset{0.15};  // m beyond the wall's faces a covering S-plane may stand
  double closed_min_height{1.8};   // m of vertical extent seen (a door leaf; clutter is lower)
  int closed_min_views{3};         // keyframes facing the opening that saw it covered

  /// "" when valid, else "<parameter>: <what is wrong>".
  std::string Validate() const;
};

/// One A-Graph doorway (a door or an opening; virtual separations are not reported) as built.
struct DoorwayDeviation {
  int doorway_id{-1};  // A-Graph doorway id
  std::string guid;    // IFC GlobalId of the door / opening, "" when the IFC had none
  std::string name;
  agraph::DoorwayKind kind{agraph::DoorwayKind::kDoor};
  int wall_id{-1};  // the A-wall it is in
  DoorwayStatus status{DoorwayStatus::kNotSeen};
  Eigen::Vector2d position{Eigen::Vector2d::Zero()};  // in B
  double width{0.0};                                  // m (default_width when unknown)
  int walked_through{0};  // keyframe steps across the opening + S-Graph doorways matched
  int rays_through{0};    // sight lines from keyframes to S-planes beyond through the opening
  int blocked_views{0};   // keyframes facing it that saw it covered and saw nothing through it
  std::vector<int> s_doorways;  // the S-Graph doorway ids matched
  std::vector<int> s_planes;    // the covering S-plane ids (CLOSED)
};

/// Classifies every door and opening of `building`'s storey walked on (the one of the walls
/// ClassifyWalls reports) against the S-Graph placed in B by `bim_T_map` corrected as
/// ClassifyWalls does (ConsensusBimTMap with `walls`): PRESENT when walked through (a keyframe
/// step across the opening, or an S-Graph doorway at it) or when at least `present_min_rays`
/// sight lines passed through it (a keyframe within view_distance to a point of an S-plane it
/// observed beyond the wall, through the opening and through no other A-wall); CLOSED when none
/// passed and at least `closed_min_views` keyframes facing the opening observed a wall-height
/// S-plane in the wall's plane spanning closed_min_cover of its width; else NOT_SEEN.
std::vector<DoorwayDeviation> ClassifyDoorways(const agraph::AGraph& building,
                                               const sgraph::SGraph& graph,
                                               const Eigen::Isometry3d& bim_T_map,
                                               const WallDeviationConfig& walls,
                                               const DoorwayDeviationConfig& config);

}  // namespace merging
}  // namespace is_graphs
