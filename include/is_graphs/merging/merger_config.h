#pragma once

#include <string>

#include "is_graphs/agraph/agraph_problem.h"
#include "is_graphs/sgraph/backend_config.h"

namespace is_graphs {
namespace merging {

/// Everything the merger (iS-Graph problem, consistency check, pose covariance) is tuned by.
/// The ROS parameters of merger_node carry the same names (config/merger.yaml).
struct MergerConfig {
  // Match constraints between the graphs (whitened by these σ, under a Huber loss).
  double surface_angle_sigma_deg{1.0};  // S-plane normal moved by B_x_M vs. A-surface normal
  double surface_offset_sigma{0.05};    // m: plane offsets
  double room_sigma{0.15};              // m: S-room centre moved by B_x_M vs. A-room centre
  double match_huber{1.0};              // Huber scale on the whitened match residuals [σ]

  // As-built deviations (issue 21): each A-wall with a matched surface gets a state (offset along
  // its plan normal, turn about z) under a Cauchy prior at zero with these σ (the plan is mostly
  // right), so that a wall built off the plan moves instead of pulling B_x_M. false: A-walls
  // are held to the plan by the A-Graph's own priors alone.
  bool estimate_wall_deviations{true};
  double wall_deviation_offset_sigma{0.03};    // m, > surface_offset_sigma / 2 (Validate)
  double wall_deviation_angle_sigma_deg{0.1};  // ° (a free turn trades with the pose's yaw)
  // A wall whose matched S-planes stand turned more than this (°) from its plan, against the
  // median turn of the matched walls, starts its turn state there with no prior on the turn:
  // its stiff prior would hold it near the plan (from zero entirely; from the turn a Cauchy tail
  // still pulls ~0.3° on 4°) and its S-planes would pull the pose's yaw instead. 90: never.
  double wall_turn_release_deg{1.0};

  // Weak prior on B_x_M at the matcher's guess (keeps a badly conditioned merge in place).
  double prior_translation_sigma{2.0};  // m
  double prior_yaw_sigma_deg{10.0};

  // Optimize the S-Graph together with B_x_M (its own factors, rebuilt from the snapshot), so
  // that the BIM corrects the drift; false: the S-Graph is held as published.
  bool optimize_sgraph{true};
  sgraph::BackendConfig sgraph;        // σ and losses of the S-Graph factors (their defaults)
  agraph::AGraphProblemConfig agraph;  // σ of the BIM priors, wall and doorway factors
  // With optimize_sgraph: only the newest this many keyframes move with B_x_M, the older ones
  // are held as the S-Graph published them (bounds the merge's cost on long runs; 0: all move).
  int window_keyframes{50};

  int max_iterations{30};
  double max_solver_time{0.5};  // s
  // A solve ends when an iteration lowers the cost by less than this share of it. What the merge
  // publishes (B_x_M, the wall states, the newest keyframe) settles within a few iterations;
  // at 1e-10 the solver went on crawling S-planes of the window along their (n, d) valleys
  // (cost -1e-4 per iteration, B_x_M < 0.01 mm), to the 30 iterations every few solves: issue
  // 22's hour, merge p50 / p99 55-79 / 104-168 ms -> 19-32 / 42-99 ms, poses within 0.1 mm on 19
  // bags (docs/merging.md). The wall states resume from the last solve, so they still converge.
  double function_tolerance{1e-5};
  int num_threads{1};

  // Consistency of a merge after each solve: a match pair is an inlier when its residual is
  // within these gates; the merge holds while enough pairs are inliers.
  double gate_angle_deg{4.0};
  double gate_offset{0.25};         // m
  double gate_room{0.6};            // m
  double min_inlier_fraction{0.6};  // of the pairs
  int min_surface_inliers{3};
  int min_room_inliers{1};  // when a merge starts (later, rooms may turn outlier and go)
  // A merge starting from a match without room pairs (wall planes alone, the matcher's
  // proposals from the first scans) needs this many surface inliers.
  int min_surface_inliers_without_rooms{6};
  double max_chi2_per_dof{9.0};  // mean whitened squared residual of the inliers
  // What the robot saw lately must lie on the BIM (CheckRecentEvidence): of the wall planes at
  // least recent_min_length long observed in the newest recent_keyframes keyframes, at least
  // recent_min_support (a share) on an A-Graph wall-surface once recent_min_planes are seen.
  int recent_keyframes{6};
  double recent_min_length{1.0};  // m
  int recent_min_planes{4};
  double recent_min_support{0.34};
  // A new UNIQUE match implying a B_x_M this far from the merged one contradicts it.
  double max_jump_translation{0.5};  // m
  double max_jump_yaw_deg{5.0};

  // The pose between revisions: the odometry since the newest merged keyframe, its scale and
  // yaw bias per metre estimated from the revision's keyframe steps (CalibrateOdometry); false:
  // the odometry as it is.
  bool calibrate_odometry{true};

  // Floors of the published pose covariance (added to the propagated B_x_M covariance).
  double pose_sigma_xy{0.02};  // m
  double pose_sigma_z{0.05};   // m
  double pose_sigma_roll_pitch_deg{0.5};
  double pose_sigma_yaw_deg{0.2};

  /// "" when valid, else "<field> <what is wrong>" (the field's name first).
  std::string Validate() const;
};

}  // namespace merging
}  // namespace is_graphs
