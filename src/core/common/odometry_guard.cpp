#include "is_graphs/common/odometry_guard.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace is_graphs {
namespace common {
namespace {

double RotationAngle(const Eigen::Isometry3d& from, const Eigen::Isometry3d& to) {
  return Eigen::AngleAxisd(from.linear().transpose() * to.linear()).angle();
}

// `step` (a motion over some time) scaled to `ratio` of that time: translation and angle.
Eigen::Isometry3d ScaleStep(const Eigen::Isometry3d& step, double ratio) {
  const Eigen::AngleAxisd turn(step.linear());
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = Eigen::AngleAxisd(turn.angle() * ratio, turn.axis()).toRotationMatrix();
  out.translation() = step.translation() * ratio;
  return out;
}

}  // namespace

std::string OdometryGuardConfig::Validate() const {
  for (const auto& [name, value] :
       {std::pair<const char*, double>{"max_linear_speed", max_linear_speed},
        {"max_angular_speed", max_angular_speed},
        {"max_linear_acceleration", max_linear_acceleration},
        {"max_angular_acceleration", max_angular_acceleration},
        {"time_reset_threshold", time_reset_threshold}})
    if (!(value > 0.0) || !std::isfinite(value)) return std::string(name) + " must be > 0";
  for (const auto& [name, value] : {std::pair<const char*, double>{"linear_slack", linear_slack},
                                    {"angular_slack", angular_slack},
                                    {"step_confirm_time", step_confirm_time}})
    if (!(value >= 0.0) || !std::isfinite(value)) return std::string(name) + " must be >= 0";
  return "";
}

const char* ToString(OdometryGuard::Verdict verdict) {
  switch (verdict) {
    case OdometryGuard::Verdict::kAccepted:
      return "accepted";
    case OdometryGuard::Verdict::kTimeBack:
      return "time went back";
    case OdometryGuard::Verdict::kNonFinite:
      return "non-finite";
    case OdometryGuard::Verdict::kOutOfOrder:
      return "out of order";
    case OdometryGuard::Verdict::kGlitch:
      return "glitch";
    case OdometryGuard::Verdict::kBridged:
      return "step bridged";
  }
  return "?";
}

void OdometryGuard::Reset() { *this = OdometryGuard(config_); }

std::string OdometryGuard::Implausible(double dt, const Eigen::Isometry3d& from,
                                       const Eigen::Isometry3d& to, double linear_speed,
                                       double angular_speed) const {
  const double distance = (to.translation() - from.translation()).norm();
  const double angle = RotationAngle(from, to);
  const double v =
      std::min(config_.max_linear_speed, linear_speed + config_.max_linear_acceleration * dt);
  const double w =
      std::min(config_.max_angular_speed, angular_speed + config_.max_angular_acceleration * dt);
  std::ostringstream why;
  why.precision(3);
  if (distance > v * dt + config_.linear_slack)
    why << "moved " << distance << " m in " << dt << " s (at most " << v * dt + config_.linear_slack
        << " m: max_linear_speed " << config_.max_linear_speed << " m/s, max_linear_acceleration "
        << config_.max_linear_acceleration << " m/s^2)";
  else if (angle > w * dt + config_.angular_slack)
    why << "turned " << angle * 180.0 / M_PI << " deg in " << dt << " s (at most "
        << (w * dt + config_.angular_slack) * 180.0 / M_PI << " deg: max_angular_speed "
        << config_.max_angular_speed << " rad/s, max_angular_acceleration "
        << config_.max_angular_acceleration << " rad/s^2)";
  return why.str();
}

OdometryGuard::Result OdometryGuard::Check(double stamp, const Eigen::Isometry3d& odom_T_base) {
  Result r;
  if (!std::isfinite(stamp) || !odom_T_base.matrix().allFinite()) {
    ++rejected_;
    r.verdict = Verdict::kNonFinite;
    r.message = !std::isfinite(stamp)                    ? "a non-finite stamp"
                : !odom_T_base.translation().allFinite() ? "a non-finite position"
                                                         : "a non-finite orientation";
    return r;
  }
  if (has_last_ && stamp < last_stamp_ - config_.time_reset_threshold) {
    std::ostringstream s;
    s << "time went back by " << last_stamp_ - stamp << " s: the odometry guard starts over";
    Reset();
    r.verdict = Verdict::kTimeBack;
    r.message = s.str();
  } else if (has_last_ && stamp <= last_stamp_) {
    ++rejected_;
    r.verdict = Verdict::kOutOfOrder;
    r.message = "a stamp not after the last accepted one";
    return r;
  } else if (has_last_) {
    const double dt = stamp - last_stamp_;
    const std::string why =
        Implausible(dt, last_reading_, odom_T_base, linear_speed_, angular_speed_);
    if (!why.empty()) {
      ++rejected_;
      r.verdict = Verdict::kGlitch;
      r.message = "faster than the robot can move: " + why;
      const bool continues = has_pending_ && stamp > pending_last_stamp_ &&
                             Implausible(stamp - pending_last_stamp_, pending_last_, odom_T_base,
                                         config_.max_linear_speed, config_.max_angular_speed)
                                 .empty();
      if (!continues) {
        has_pending_ = true;
        pending_first_stamp_ = stamp;
        pending_first_ = odom_T_base;
      }
      pending_last_stamp_ = stamp;
      pending_last_ = odom_T_base;
      if (config_.step_confirm_time <= 0.0 ||
          pending_last_stamp_ - pending_first_stamp_ < config_.step_confirm_time)
        return r;
      // A lasting step: the reading goes on from where the last accepted one was.
      const Eigen::Vector3d jump = pending_first_.translation() - last_reading_.translation();
      std::ostringstream s;
      s.precision(3);
      s << "odometry stepped by " << jump.norm() << " m, "
        << RotationAngle(last_reading_, pending_first_) * 180.0 / M_PI << " deg at " << std::fixed
        << pending_first_stamp_ << " s and stayed for "
        << pending_last_stamp_ - pending_first_stamp_
        << " s: bridged (taken as a jump of the odometry frame, not motion of the robot)";
      // Across the step itself the robot moved as in the last accepted step (scaled to the time).
      const double jump_dt = pending_first_stamp_ - last_stamp_;
      const Eigen::Isometry3d across =
          last_dt_ > 0.0 ? ScaleStep(last_step_, std::min(jump_dt / last_dt_, 3.0))
                         : Eigen::Isometry3d::Identity();
      correction_ = correction_ * last_reading_ * across * pending_first_.inverse();
      const double span = pending_last_stamp_ - pending_first_stamp_;
      linear_speed_ = (pending_last_.translation() - pending_first_.translation()).norm() / span;
      angular_speed_ = RotationAngle(pending_first_, pending_last_) / span;
      --rejected_;  // this one is used after all
      ++bridged_;
      has_pending_ = false;
      last_dt_ = 0.0;
      last_stamp_ = stamp;
      last_reading_ = odom_T_base;
      r.verdict = Verdict::kBridged;
      r.message = s.str();
      r.odom_T_base = correction_ * odom_T_base;
      return r;
    }
    linear_speed_ = (odom_T_base.translation() - last_reading_.translation()).norm() / dt;
    angular_speed_ = RotationAngle(last_reading_, odom_T_base) / dt;
    last_step_ = last_reading_.inverse() * odom_T_base;
    last_dt_ = dt;
  }
  has_pending_ = false;
  has_last_ = true;
  last_stamp_ = stamp;
  last_reading_ = odom_T_base;
  r.odom_T_base = correction_ * odom_T_base;
  return r;
}

}  // namespace common
}  // namespace is_graphs
