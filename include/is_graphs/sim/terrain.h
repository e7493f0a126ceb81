#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "is_graphs/common/result.h"
#include "is_graphs/sim/embree_scene.h"
#include "is_graphs/sim/trajectory.h"

namespace is_graphs {
namespace sim {

/// How the robot finds the ground under its path (issue 22: stairs).
struct TerrainConfig {
  double sample_step{0.05};  // m of path between two ground samples
  double max_step{0.3};      // m: the most the ground may rise or fall between two samples
  double half_length{0.4};   // m: from the body's centre to the front and hind feet
  double stair_rise{0.3};    // m: a walk whose ground rises or falls more is a stair flight
  std::string Validate() const;
};

/// The ground along a trajectory's walked path, sampled every `sample_step` m: the highest
/// upward-facing surface of the scene within `max_step` of the previous sample (a stair tread,
/// a landing, the next storey's floor). The body rests on its front and hind feet: its floor
/// height is their mean and its pitch their slope, so it climbs a flight on the flight's
/// incline, not step by step. Flat ground gives the start's floor height and no pitch.
class TerrainProfile {
 public:
  /// Flat ground at `floor_z` (a route on one floor; a kidnap's second route).
  static TerrainProfile Flat(double floor_z);
  /// The ground under `trajectory`'s path in `scene`, from the start's floor `floor_z`. Errors
  /// name where no ground was found, or where it rose or fell more than `max_step`.
  static Result<TerrainProfile> Build(const EmbreeScene& scene, const Trajectory& trajectory,
                                      double floor_z, const TerrainConfig& config);

  /// Ground height at `distance` m along the path (linear between samples, clamped).
  double GroundAt(double distance) const;
  /// The body's floor height (mean of the feet's ground) and pitch (rad, positive nose down,
  /// as a rotation about the body's y axis) at `distance`.
  double BodyFloor(double distance) const;
  double BodyPitch(double distance) const;
  /// The largest rise or fall of the ground along [from, to] (m).
  double HeightChange(double from, double to) const;
  bool flat() const { return heights_.size() <= 1; }

 private:
  double step_{0.05};
  double half_length_{0.4};
  std::vector<double> heights_;  // at 0, step, 2 step, ...
};

/// The cruise speed factor for each walk of `trajectory` on `terrain`: `stairs_speed / speed`
/// for walks that rise or fall more than `config.stair_rise` (stair flights), else 1.
LegSpeed StairLegSpeed(const Trajectory& trajectory, const TerrainProfile& terrain,
                       const TerrainConfig& config, double speed, double stairs_speed);

}  // namespace sim
}  // namespace is_graphs
