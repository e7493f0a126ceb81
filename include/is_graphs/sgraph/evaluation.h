#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace sgraph {

/// Measuring an S-Graph against the truth of a simulated run: ground-truth poses (base_link in
/// the BIM frame) and the building's A-Graph. Used by bench_sgraph and the rostest.
struct StampedPose {
  double stamp{0.0};
  Eigen::Isometry3d pose{Eigen::Isometry3d::Identity()};
};

/// Ground truth interpolated at `stamp` (nullopt outside it or across gaps > 0.2 s).
std::optional<Eigen::Isometry3d> TruthAt(const std::vector<StampedPose>& truth, double stamp);

/// The rigid transform T minimizing Σ |gt_i − T est_i|² (Umeyama, no scale): what evo's
/// `--align` does.
Eigen::Isometry3d AlignPositions(const std::vector<Eigen::Vector3d>& estimate,
                                 const std::vector<Eigen::Vector3d>& truth);

/// The transform T = (yaw about z, translation) minimizing Σ |gt_i − T est_i|²: the alignment
/// for two gravity-aligned frames (the S-Graph's map and the BIM are both z-up). A 6-DoF fit of
/// the nearly planar trajectory of a walking robot leaves roll and pitch to the centimetre bob
/// of its gait, and a few degrees of tilt there would tilt every aligned wall by as much.
/// Where the positions do not fix the yaw (one keyframe, or all within 0.5 m: a robot that has
/// only turned on the spot), it comes from the headings `estimate_yaw` and `truth_yaw` (rad,
/// each pair's difference averaged on the circle) when they are given; else it is 0.
Eigen::Isometry3d AlignPositionsYaw(const std::vector<Eigen::Vector3d>& estimate,
                                    const std::vector<Eigen::Vector3d>& truth,
                                    const std::vector<double>& estimate_yaw = {},
                                    const std::vector<double>& truth_yaw = {});

struct TrajectoryError {
  int keyframes{0};
  double sgraph_rmse{0.0};  // aligned APE (translation) of the optimized keyframe poses
  double odom_rmse{0.0};    // the same for the odometry poses of the keyframes
  Eigen::Isometry3d bim_T_map{Eigen::Isometry3d::Identity()};  // the S-Graph alignment
  // The same with the gravity-aware alignment (AlignPositionsYaw): how the map is compared
  // with the BIM's planes and rooms.
  double sgraph_rmse_gravity{0.0};
  double odom_rmse_gravity{0.0};
  Eigen::Isometry3d bim_T_map_gravity{Eigen::Isometry3d::Identity()};
};
TrajectoryError EvaluateTrajectory(const SGraph& graph, const std::vector<StampedPose>& truth);

struct PlaneError {
  int plane{0};
  int surface{-1};        // the A-Graph wall-surface it lies on; −1: none within 0.3 m / 10°
  double distance{0.0};   // worst |distance| of the plane's extent ends to the surface [m]
  double angle_deg{0.0};  // between the normals
};
/// Every vertical S-Graph plane with at least `min_points` points, in bim via `bim_T_map`,
/// against the wall-surfaces of the A-Graph (same facing: both normals point into rooms).
std::vector<PlaneError> EvaluatePlanes(const SGraph& graph, const agraph::AGraph& building,
                                       const Eigen::Isometry3d& bim_T_map, int min_points);

/// One S-Graph room against the building: the A-Graph room its centre lies in (-1: none) and
/// whether it counts as found, a duplicate (a second S-room in that A-room) or outside.
struct RoomVerdict {
  int room{0};     // S-Graph room id
  int a_room{-1};  // index into AGraph::rooms
  Eigen::Vector2d center_bim{Eigen::Vector2d::Zero()};
  enum class Kind { kFound, kDuplicate, kOutside } kind{Kind::kFound};
};

/// Rooms against the BIM rooms the robot walked through (A-Graph rooms holding ≥ 2 keyframes
/// by ground truth). An S-Graph room or corridor is correct when its centre (in bim) lies in a
/// walked room that no earlier S-Graph room took; false otherwise (outside the walked rooms, or
/// a second S-Graph room for one BIM room).
struct RoomEvaluation {
  std::vector<RoomVerdict> verdicts;  // one per S-Graph room, in the graph's order
  int walked{0};                      // A-Graph rooms with ≥ 2 keyframes inside
  int found{0};                       // of those, rooms with an S-Graph room centred inside
  int detected{0};                    // S-Graph rooms and corridors
  int false_rooms{0};  // S-Graph rooms centred outside the walked rooms, plus duplicates
  int duplicates{0};   // of those, second (third...) S-Graph rooms in one BIM room
};
RoomEvaluation EvaluateRooms(const SGraph& graph, const agraph::AGraph& building,
                             const std::vector<StampedPose>& truth,
                             const Eigen::Isometry3d& bim_T_map);

}  // namespace sgraph
}  // namespace is_graphs
