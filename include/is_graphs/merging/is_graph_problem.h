#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <map>
#include <string>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/merging/merger_config.h"
#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace merging {

/// The match pairs a merge uses: S-Graph id -> A-Graph id(s). An S-room matches one A-room; an
/// S-plane matches one A-wall-surface, or each of several collinear ones (a corridor wall split
/// by doorways), which then share its weight.
struct MatchPairs {
  std::map<int, int> rooms;                  // S-room id -> A-room id
  std::map<int, std::vector<int>> surfaces;  // S-plane id -> A-wall-surface ids
  bool empty() const { return rooms.empty() && surfaces.empty(); }
};

/// One match pair's residual after the solve: the published S-Graph node moved by the solved
/// B_x_M against the solved A-Graph node (so a merge that bends the S-Graph cannot hide it).
struct PairResidual {
  int s_id{0};
  int a_id{0};
  bool corridor{false};   // rooms: an S-corridor (only the component across it counts)
  bool used{true};        // false when the pair could not enter the problem (opposed normals)
  double angle_deg{0.0};  // surfaces: angle between the moved S-normal and the A-normal
  double offset{0.0};     // surfaces: |d_b − d_a| [m]
  double distance{0.0};   // rooms: horizontal centre distance (across, for corridors) [m]
  double chi2{0.0};       // squared whitened residual
  int dof{0};
};

/// One A-wall's as-built deviation as the merge estimated it (config.estimate_wall_deviations),
/// the state DeviatedSurfaceMatchCost moves the wall by.
struct WallDeviationEstimate {
  int wall_id{-1};
  double offset{0.0};        // m along the wall's plan normal (its surface_a's), at its centre
  double angle{0.0};         // rad, anticlockwise about z, from the plan to the build
  double offset_sigma{0.0};  // 1-σ of offset [m] and angle [rad]; 0 when not computed
  double angle_sigma{0.0};
  int pairs{0};  // surface pairs resting on it
};

/// The solved iS-Graph: B_x_M, its covariance, the S-Graph keyframes corrected by the BIM and
/// every match pair's residual.
struct MergeSolution {
  bool usable{false};
  Eigen::Vector3d bim_x_map{Eigen::Vector3d::Zero()};       // x, y, yaw
  double z{0.0};                                            // height of M in B (not estimated)
  Eigen::Matrix3d covariance{Eigen::Matrix3d::Identity()};  // of (x, y, yaw)
  bool covariance_ok{false};
  std::map<int, Eigen::Isometry3d> keyframes;  // id -> optimized pose in M
  std::vector<PairResidual> surfaces;
  std::vector<PairResidual> rooms;
  std::vector<WallDeviationEstimate> walls;  // by wall id; empty unless estimated
  int iterations{0};
  int residual_blocks{0};
  double seconds{0.0};
  double initial_cost{0.0};
  double final_cost{0.0};
  std::string message;

  /// B_x_M as a gravity-aligned isometry, with z.
  Eigen::Isometry3d BimTMap() const;
};

/// The walls seen turned off the plan (SolveMerge, before the solve). `turns`: per wall, the
/// turns (rad, about z, plan to build) its matched S-planes show under the current B_x_M. A wall
/// whose mean turn differs from the median over the walls (a yaw error of B_x_M turns every wall
/// alike) by more than `release` is returned with that difference; fewer than 3 walls give no
/// median and nothing.
std::map<int, double> TurnedWalls(const std::map<int, std::vector<double>>& turns, double release);

/// Where the walls' turn states start: each wall of `turned` (TurnedWalls) at its turn, unless its
/// state already stands at least half-way there; the others as in `starts`. From zero, a Cauchy
/// prior (σ 0.1°, steepest within a few σ) would hold a wall turned 4° at the plan.
std::map<int, Eigen::Vector2d> ReleasedTurns(const std::map<int, double>& turned,
                                             std::map<int, Eigen::Vector2d> starts);

/// Builds the iS-Graph problem in one ceres::Problem and solves it (SPARSE_NORMAL_CHOLESKY on
/// SuiteSparse); B_x_M's covariance with ceres::Covariance (SPARSE_QR on SuiteSparse).
///   A-Graph: agraph::AGraphProblem::AddTo (BIM priors, wall-centre and doorway factors).
///   S-Graph (config.optimize_sgraph): its factors rebuilt from the snapshot (odometry,
///     keyframe–plane, room–plane, corridor–plane, floor–room; the first keyframe fixed as the
///     gauge of M; the room and floor offsets measured on the snapshot). Otherwise the S-Graph
///     nodes used by the match are held constant.
///   Match: SurfaceMatchCost per surface pair (DeviatedSurfaceMatchCost for a surface of a wall
///     when config.estimate_wall_deviations, with one WallDeviationPriorCost per such wall under
///     a Cauchy loss, none on the turn of a wall seen turned: TurnedWalls), RoomMatchCost /
///     CorridorMatchCost per room pair (Huber; DeviatedRoomMatchCost, the A-room's centre moved
///     with its walls' offsets (RoomCentreShifts), when its walls have deviation states),
///     TransformPriorCost at `prior` (the matcher's guess).
/// The pair residuals are against the plan (a deviation does not make a pair consistent).
/// `initial` and `prior` are (x, y, yaw); `z` is the height of M in B. Pairs naming nodes that
/// are not in the graphs are skipped. The A-Graph must be valid (agraph::ValidateAGraph).
/// `initial_deviations` (wall id -> offset, angle): where the wall deviation states start (the
/// previous solve's; zero for the walls not in it), so a wall off the plan need not be found
/// again from the plan on every revision; a wall seen turned is started at its turn
/// (ReleasedTurns, config.wall_turn_release_deg).
MergeSolution SolveMerge(const agraph::AGraph& a_graph, const sgraph::SGraph& s_graph,
                         const MatchPairs& pairs, const Eigen::Vector3d& initial,
                         const Eigen::Vector3d& prior, double z, const MergerConfig& config,
                         const std::map<int, Eigen::Vector2d>& initial_deviations = {});

}  // namespace merging
}  // namespace is_graphs
