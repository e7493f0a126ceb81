#pragma once

#include <Eigen/Geometry>

#include "is_graphs/sim/scenario_config.h"
#include "is_graphs/sim/trajectory.h"

namespace is_graphs {
namespace sim {

/// Body sway of a trotting quadruped: vertical bob and pitch at the step frequency, roll at half
/// of it (left/right alternation), with amplitudes scaled by the gait activity (0 at rest, 1
/// when walking at `full_activity_speed` or turning). Deterministic: a function of t only.
class GaitModel {
 public:
  explicit GaitModel(const GaitConfig& config) : config_(config) {}

  /// Activity in [0, 1] from the planned speed and yaw rate (continuous in t).
  double Activity(const PlanarState& state) const;
  /// (roll, pitch, dz) at time t for `activity`.
  Eigen::Vector3d Sway(double t, double activity) const;
  const GaitConfig& config() const { return config_; }

 private:
  GaitConfig config_;
};

/// base_link in bim at time t: the planar trajectory at floor height + standing height, with
/// the gait sway on top.
class RobotMotion {
 public:
  RobotMotion(Trajectory trajectory, const GaitConfig& gait, double floor_z)
      : trajectory_(std::move(trajectory)), gait_(gait), floor_z_(floor_z) {}

  Eigen::Isometry3d BasePose(double t) const;
  const Trajectory& trajectory() const { return trajectory_; }
  double floor_z() const { return floor_z_; }
  double Duration() const { return trajectory_.Duration(); }

 private:
  Trajectory trajectory_;
  GaitModel gait_;
  double floor_z_;
};

}  // namespace sim
}  // namespace is_graphs
