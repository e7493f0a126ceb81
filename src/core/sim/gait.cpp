#include "is_graphs/sim/gait.h"

#include <algorithm>
#include <cmath>

namespace is_graphs {
namespace sim {

double GaitModel::Activity(const PlanarState& state) const {
  constexpr double kFullActivityYawRate = 0.3;  // rad/s: turning in place steps as walking does
  const double a = std::max(std::abs(state.speed) / config_.full_activity_speed,
                            std::abs(state.yaw_rate) / kFullActivityYawRate);
  return std::min(1.0, a);
}

Eigen::Vector3d GaitModel::Sway(double t, double activity) const {
  const double w = 2.0 * M_PI * config_.step_frequency_hz;
  const double deg = M_PI / 180.0;
  return activity * Eigen::Vector3d(config_.roll_amplitude_deg * deg * std::sin(0.5 * w * t),
                                    config_.pitch_amplitude_deg * deg * std::sin(w * t + 0.9),
                                    config_.bob_amplitude * std::sin(w * t));
}

int RobotMotion::LegAt(double t) const {
  // A carry at a multiple of the scan or odometry period starts exactly there whichever way
  // k * period rounds.
  constexpr double kTolerance = 1e-9;
  int leg = 0;
  while (leg + 1 < NumLegs() && t >= legs_[leg + 1].start - kTolerance) ++leg;
  return leg;
}

Eigen::Isometry3d RobotMotion::BasePose(double t) const {
  const Leg& leg = legs_[LegAt(t)];
  const PlanarState state = leg.trajectory.StateAt(t - leg.start);
  const Eigen::Vector3d sway = gait_.Sway(t, gait_.Activity(state));
  const double floor = leg.terrain.BodyFloor(state.distance);
  const double incline = leg.terrain.BodyPitch(state.distance);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = (Eigen::AngleAxisd(state.pose.z(), Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(incline + sway.y(), Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(sway.x(), Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  pose.translation() = Eigen::Vector3d(state.pose.x(), state.pose.y(),
                                       floor + gait_.config().standing_height + sway.z());
  return pose;
}

}  // namespace sim
}  // namespace is_graphs
