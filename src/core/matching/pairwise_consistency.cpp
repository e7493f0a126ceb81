#include "is_graphs/matching/pairwise_consistency.h"

#include <cmath>

namespace is_graphs {
namespace matching {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

/// The turn from a to b as a (cos, sin) pair scaled by |a||b|: a complex a̅·b.
Eigen::Vector2d Turn(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return {a.dot(b), a.x() * b.y() - a.y() * b.x()};
}

double Gaussian(double error, double tolerance) {
  if (!(std::abs(error) <= tolerance)) return 0.0;
  const double sigma = 0.5 * tolerance;
  return std::exp(-0.5 * error * error / (sigma * sigma));
}

}  // namespace

double SurfacePairConsistency(const PointNormal& s1, const PointNormal& s2, const PointNormal& a1,
                              const PointNormal& a2, double angle_tolerance_rad,
                              double distance_tolerance) {
  // The S turn less the A turn, in one atan2: the angle of turn_s · conj(turn_a).
  const Eigen::Vector2d ts = Turn(s1.normal, s2.normal), ta = Turn(a1.normal, a2.normal);
  const double angle_error =
      std::abs(std::atan2(ts.y() * ta.x() - ts.x() * ta.y(), ts.x() * ta.x() + ts.y() * ta.y()));
  const double distance_error = (s1.point - s2.point).norm() - (a1.point - a2.point).norm();
  return Gaussian(angle_error, angle_tolerance_rad) * Gaussian(distance_error, distance_tolerance);
}

double RoomPairConsistency(const RoomCorrespondence& i, const RoomCorrespondence& j,
                           const MatcherConfig& config) {
  const double yaw_error = AngleDistance(i.yaw, j.yaw);
  const double yaw_weight = Gaussian(yaw_error, config.yaw_tolerance_deg * kDegToRad);
  if (yaw_weight == 0.0) return 0.0;
  const Eigen::Vector2d ds = Pose2{i.yaw, Eigen::Vector2d::Zero()}.Rotate(j.s_centre - i.s_centre);
  const Eigen::Vector2d da = j.a_centre - i.a_centre;
  Eigen::Vector2d error = ds - da;
  // A corridor's centre is free along its axis: drop that component.
  for (const RoomCorrespondence* c : {&i, &j}) {
    if (c->axis_free) error -= c->axis_b * c->axis_b.dot(error);
  }
  const double tolerance = 2.0 * config.centre_tolerance + config.lever_arm_slack * da.norm();
  return yaw_weight * Gaussian(error.norm(), tolerance);
}

}  // namespace matching
}  // namespace is_graphs
