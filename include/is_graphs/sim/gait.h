#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "is_graphs/sim/scenario_config.h"
#include "is_graphs/sim/terrain.h"
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

/// base_link in bim at time t: the planar trajectory at the terrain's height under it (the
/// floor, or a stair flight's incline, with its pitch) + standing height, with the gait sway on
/// top. A kidnapped robot has more than one leg: from each carry's time on it walks that carry's
/// trajectory (whose t = 0 is the carry's time).
class RobotMotion {
 public:
  RobotMotion(Trajectory trajectory, const GaitConfig& gait, double floor_z, TerrainProfile terrain)
      : gait_(gait), floor_z_(floor_z) {
    legs_.push_back({0.0, std::move(trajectory), std::move(terrain)});
  }
  RobotMotion(Trajectory trajectory, const GaitConfig& gait, double floor_z)
      : RobotMotion(std::move(trajectory), gait, floor_z, TerrainProfile::Flat(floor_z)) {}

  /// From `time` on (> the last leg's start), the robot walks `next` on the start's floor: it is
  /// carried there instantly.
  void Carry(double time, Trajectory next) {
    legs_.push_back({time, std::move(next), TerrainProfile::Flat(floor_z_)});
  }

  Eigen::Isometry3d BasePose(double t) const;
  /// The leg walked at time t: 0 before the first carry, 1 after it, ...
  int LegAt(double t) const;
  /// The trajectory of leg i, and when it starts.
  const Trajectory& trajectory(int leg = 0) const { return legs_[leg].trajectory; }
  double LegStart(int leg) const { return legs_[leg].start; }
  int NumLegs() const { return static_cast<int>(legs_.size()); }
  double floor_z() const { return floor_z_; }
  /// The end of the last leg.
  double Duration() const { return legs_.back().start + legs_.back().trajectory.Duration(); }

 private:
  struct Leg {
    double start;
    Trajectory trajectory;
    TerrainProfile terrain;
  };
  std::vector<Leg> legs_;
  GaitModel gait_;
  double floor_z_;
};

}  // namespace sim
}  // namespace is_graphs
