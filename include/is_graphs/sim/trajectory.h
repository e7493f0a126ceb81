#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <vector>

#include "is_graphs/common/result.h"
#include "is_graphs/sim/scenario_config.h"

namespace is_graphs {
namespace sim {

/// A planar target of the walk: reach `position`, then (optionally) turn to `yaw`; stand still
/// for the configured pause there when `pause`.
struct PlanarWaypoint {
  Eigen::Vector2d position{Eigen::Vector2d::Zero()};
  std::optional<double> yaw;
  bool pause{true};
};

/// The planned planar motion at one instant: pose (x, y, yaw) in bim, forward speed (m/s) and
/// yaw rate (rad/s), and the path length walked so far (m: where on the terrain profile).
struct PlanarState {
  Eigen::Vector3d pose{Eigen::Vector3d::Zero()};
  double speed{0.0};
  double yaw_rate{0.0};
  double distance{0.0};
};

/// The cruise speed factor of the walk from `from` to `to` (1: the configured speed; stairs are
/// walked slower).
using LegSpeed = std::function<double(const Eigen::Vector2d& from, const Eigen::Vector2d& to)>;

/// Time-parametrized planar walk: turn in place towards the next waypoint, walk straight to it
/// (trapezoidal speed profile: C¹ position, continuous speed), pause, repeat. Evaluation is
/// O(log n) and exact at any t (no integration), so each LiDAR firing gets its own pose.
class Trajectory {
 public:
  /// Starts at `start` (x, y, yaw) after `config.pause`; visits `waypoints` in order. With
  /// `config.loop`, the route is walked back and forth until `min_duration` is covered.
  static Result<Trajectory> Build(const Eigen::Vector3d& start,
                                  const std::vector<PlanarWaypoint>& waypoints,
                                  const TrajectoryConfig& config, double min_duration = 0.0,
                                  const LegSpeed& leg_speed = nullptr);

  /// State at time t in [0, Duration()] from the start (clamped outside).
  PlanarState StateAt(double t) const;
  double Duration() const { return segments_.empty() ? 0.0 : segments_.back().t_end; }
  /// Length of the walked path, m.
  double PathLength() const { return path_length_; }
  /// (x, y) at `distance` (m) along the walked path (clamped to [0, PathLength()]).
  Eigen::Vector2d PositionAtDistance(double distance) const;
  /// The straight walks, in order: start, end (x, y) and the path length at their start.
  struct Walk {
    Eigen::Vector2d from, to;
    double distance_begin;
  };
  std::vector<Walk> Walks() const;

 private:
  enum class Kind { kPause, kTurn, kWalk };
  struct Segment {
    Kind kind;
    double t_begin, t_end;
    Eigen::Vector3d from;   // pose at t_begin
    double amount;          // walk: distance (m), turn: signed angle (rad)
    double v_max, accel;    // of the trapezoid (m/s, rad/s)
    double distance_begin;  // path length walked at t_begin
  };
  void Append(Kind kind, const Eigen::Vector3d& from, double amount, double v_max, double accel,
              double duration);
  void AddLeg(Eigen::Vector3d* pose, const PlanarWaypoint& target, const TrajectoryConfig& c,
              const LegSpeed& leg_speed);

  std::vector<Segment> segments_;
  double path_length_{0.0};
};

/// Trapezoidal profile over `amount` (> 0) with peak `v_max` and acceleration `accel`:
/// total time, and position/speed at time tau.
double TrapezoidDuration(double amount, double v_max, double accel);
void TrapezoidAt(double amount, double v_max, double accel, double tau, double* position,
                 double* speed);

}  // namespace sim
}  // namespace is_graphs
