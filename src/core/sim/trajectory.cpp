#include "is_graphs/sim/trajectory.h"

#include <algorithm>
#include <cmath>

#include "is_graphs/geometry/se3.h"

namespace is_graphs {
namespace sim {

double TrapezoidDuration(double amount, double v_max, double accel) {
  if (amount <= 0.0) return 0.0;
  if (amount <= v_max * v_max / accel) return 2.0 * std::sqrt(amount / accel);  // triangle
  return v_max / accel + amount / v_max;
}

void TrapezoidAt(double amount, double v_max, double accel, double tau, double* position,
                 double* speed) {
  const double total = TrapezoidDuration(amount, v_max, accel);
  tau = std::clamp(tau, 0.0, total);
  const double v_peak = std::min(v_max, std::sqrt(amount * accel));
  const double t_acc = v_peak / accel;
  const double d_acc = 0.5 * v_peak * t_acc;
  if (tau < t_acc) {
    *position = 0.5 * accel * tau * tau;
    *speed = accel * tau;
  } else if (tau <= total - t_acc) {
    *position = d_acc + v_peak * (tau - t_acc);
    *speed = v_peak;
  } else {
    const double r = total - tau;
    *position = amount - 0.5 * accel * r * r;
    *speed = accel * r;
  }
}

void Trajectory::Append(Kind kind, const Eigen::Vector3d& from, double amount, double v_max,
                        double accel, double duration) {
  if (duration <= 0.0) return;
  const double t0 = Duration();
  segments_.push_back({kind, t0, t0 + duration, from, amount, v_max, accel, path_length_});
}

void Trajectory::AddLeg(Eigen::Vector3d* pose, const PlanarWaypoint& target,
                        const TrajectoryConfig& c, const LegSpeed& leg_speed) {
  const double turn_rate = c.turn_rate_deg * M_PI / 180.0;
  const double turn_accel = c.turn_acceleration_deg * M_PI / 180.0;
  auto turn_to = [&](double yaw) {
    const double delta = geometry::NormalizeAngle(yaw - pose->z());
    if (std::abs(delta) < 1e-3) return;
    Append(Kind::kTurn, *pose, delta, turn_rate, turn_accel,
           TrapezoidDuration(std::abs(delta), turn_rate, turn_accel));
    pose->z() = geometry::NormalizeAngle(pose->z() + delta);
  };
  const Eigen::Vector2d step = target.position - pose->head<2>();
  const double distance = step.norm();
  if (distance > 1e-3) {
    turn_to(std::atan2(step.y(), step.x()));
    const double speed =
        c.speed *
        (leg_speed ? std::clamp(leg_speed(pose->head<2>(), target.position), 0.05, 1.0) : 1.0);
    Append(Kind::kWalk, *pose, distance, speed, c.acceleration,
           TrapezoidDuration(distance, speed, c.acceleration));
    pose->head<2>() = target.position;
    path_length_ += distance;
  }
  if (target.yaw) turn_to(*target.yaw);
  if (target.pause) Append(Kind::kPause, *pose, 0.0, 0.0, 1.0, c.pause);
}

Result<Trajectory> Trajectory::Build(const Eigen::Vector3d& start,
                                     const std::vector<PlanarWaypoint>& waypoints,
                                     const TrajectoryConfig& config, double min_duration,
                                     const LegSpeed& leg_speed) {
  const std::string e = config.Validate();
  if (!e.empty()) return Result<Trajectory>::Error(e);
  Trajectory t;
  Eigen::Vector3d pose = start;
  pose.z() = geometry::NormalizeAngle(pose.z());
  t.Append(Kind::kPause, pose, 0.0, 0.0, 1.0, std::max(config.pause, 1e-3));
  for (const PlanarWaypoint& w : waypoints) t.AddLeg(&pose, w, config, leg_speed);
  if (config.loop && !waypoints.empty() && t.path_length_ > 0.1) {
    // Back and forth: reversed route (ending at the start), then forward again, ...
    std::vector<PlanarWaypoint> back(waypoints.rbegin() + 1, waypoints.rend());
    back.push_back({start.head<2>(), std::nullopt, true});
    bool forward = false;
    while (t.Duration() < min_duration) {
      for (const PlanarWaypoint& w : forward ? waypoints : back)
        t.AddLeg(&pose, w, config, leg_speed);
      forward = !forward;
    }
  }
  if (t.Duration() < min_duration) {
    t.Append(Kind::kPause, pose, 0.0, 0.0, 1.0, min_duration - t.Duration());
  }
  return Result<Trajectory>::Ok(std::move(t));
}

PlanarState Trajectory::StateAt(double t) const {
  PlanarState state;
  if (segments_.empty()) return state;
  t = std::clamp(t, 0.0, Duration());
  auto it = std::upper_bound(segments_.begin(), segments_.end(), t,
                             [](double value, const Segment& s) { return value < s.t_end; });
  if (it == segments_.end()) --it;
  const Segment& s = *it;
  state.pose = s.from;
  state.distance = s.distance_begin;
  const double tau = t - s.t_begin;
  double position = 0.0, speed = 0.0;
  switch (s.kind) {
    case Kind::kPause:
      break;
    case Kind::kWalk:
      TrapezoidAt(s.amount, s.v_max, s.accel, tau, &position, &speed);
      state.pose.x() += position * std::cos(s.from.z());
      state.pose.y() += position * std::sin(s.from.z());
      state.speed = speed;
      state.distance += position;
      break;
    case Kind::kTurn: {
      const double sign = s.amount < 0.0 ? -1.0 : 1.0;
      TrapezoidAt(std::abs(s.amount), s.v_max, s.accel, tau, &position, &speed);
      state.pose.z() = geometry::NormalizeAngle(s.from.z() + sign * position);
      state.yaw_rate = sign * speed;
      break;
    }
  }
  return state;
}

std::vector<Trajectory::Walk> Trajectory::Walks() const {
  std::vector<Walk> out;
  for (const Segment& s : segments_) {
    if (s.kind != Kind::kWalk) continue;
    const Eigen::Vector2d from = s.from.head<2>();
    const Eigen::Vector2d dir(std::cos(s.from.z()), std::sin(s.from.z()));
    out.push_back({from, from + s.amount * dir, s.distance_begin});
  }
  return out;
}

Eigen::Vector2d Trajectory::PositionAtDistance(double distance) const {
  const Segment* last = nullptr;
  for (const Segment& s : segments_) {  // walks in order of distance_begin
    if (s.kind != Kind::kWalk) continue;
    if (distance < s.distance_begin) break;
    last = &s;
  }
  if (!last) {
    if (segments_.empty()) return Eigen::Vector2d::Zero();
    return segments_.front().from.head<2>();
  }
  const double along = std::clamp(distance - last->distance_begin, 0.0, last->amount);
  return last->from.head<2>() +
         along * Eigen::Vector2d(std::cos(last->from.z()), std::sin(last->from.z()));
}

}  // namespace sim
}  // namespace is_graphs
