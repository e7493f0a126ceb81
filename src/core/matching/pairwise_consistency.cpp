#include "is_graphs/matching/pairwise_consistency.h"

#include <cmath>

namespace is_graphs {
namespace matching {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

double SignedAngle(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
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
  const double angle_error =
      AngleDistance(SignedAngle(s1.normal, s2.normal), SignedAngle(a1.normal, a2.normal));
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
