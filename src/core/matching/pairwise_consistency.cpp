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

/// The two errors SurfacePairConsistency weighs: the signed turn's and the distance's.
double SurfaceDistanceError(const PointNormal& s1, const PointNormal& s2, const PointNormal& a1,
                            const PointNormal& a2) {
  return (s1.point - s2.point).norm() - (a1.point - a2.point).norm();
}
double SurfaceAngleError(const PointNormal& s1, const PointNormal& s2, const PointNormal& a1,
                         const PointNormal& a2) {
  // The S turn less the A turn, in one atan2: the angle of turn_s · conj(turn_a).
  const Eigen::Vector2d ts = Turn(s1.normal, s2.normal), ta = Turn(a1.normal, a2.normal);
  return std::abs(std::atan2(ts.y() * ta.x() - ts.x() * ta.y(), ts.x() * ta.x() + ts.y() * ta.y()));
}

/// The yaw error and the centre displacement error RoomPairConsistency weighs, and the latter's
/// tolerance.
struct RoomErrors {
  double yaw{0.0};
  double centre{0.0};
  double centre_tolerance{0.0};
};
RoomErrors RoomPairErrors(const RoomCorrespondence& i, const RoomCorrespondence& j,
                          const MatcherConfig& config, bool with_centre) {
  RoomErrors out;
  out.yaw = AngleDistance(i.yaw, j.yaw);
  if (!with_centre) return out;
  const Eigen::Vector2d ds = Pose2{i.yaw, Eigen::Vector2d::Zero()}.Rotate(j.s_centre - i.s_centre);
  const Eigen::Vector2d da = j.a_centre - i.a_centre;
  Eigen::Vector2d error = ds - da;
  // A corridor's centre is free along its axis: drop that component.
  for (const RoomCorrespondence* c : {&i, &j}) {
    if (c->axis_free) error -= c->axis_b * c->axis_b.dot(error);
  }
  out.centre = error.norm();
  out.centre_tolerance = 2.0 * config.centre_tolerance + config.lever_arm_slack * da.norm();
  return out;
}

bool Within(double error, double tolerance) { return std::abs(error) <= tolerance; }

}  // namespace

double SurfacePairConsistency(const PointNormal& s1, const PointNormal& s2, const PointNormal& a1,
                              const PointNormal& a2, double angle_tolerance_rad,
                              double distance_tolerance) {
  return Gaussian(SurfaceAngleError(s1, s2, a1, a2), angle_tolerance_rad) *
         Gaussian(SurfaceDistanceError(s1, s2, a1, a2), distance_tolerance);
}

bool SurfacePairsAgree(const PointNormal& s1, const PointNormal& s2, const PointNormal& a1,
                       const PointNormal& a2, double cos_angle_tolerance,
                       double distance_tolerance) {
  if (!Within(SurfaceDistanceError(s1, s2, a1, a2), distance_tolerance)) return false;
  // The angle between the two turns within the tolerance, as a cosine: their dot product
  // against the tolerance's cosine times their lengths.
  const Eigen::Vector2d ts = Turn(s1.normal, s2.normal), ta = Turn(a1.normal, a2.normal);
  return ts.dot(ta) >= cos_angle_tolerance * std::sqrt(ts.squaredNorm() * ta.squaredNorm());
}

double RoomPairConsistency(const RoomCorrespondence& i, const RoomCorrespondence& j,
                           const MatcherConfig& config) {
  const double yaw_tolerance = config.yaw_tolerance_deg * kDegToRad;
  RoomErrors e = RoomPairErrors(i, j, config, false);
  const double yaw_weight = Gaussian(e.yaw, yaw_tolerance);
  if (yaw_weight == 0.0) return 0.0;
  e = RoomPairErrors(i, j, config, true);
  return yaw_weight * Gaussian(e.centre, e.centre_tolerance);
}

bool RoomPairsAgree(const RoomCorrespondence& i, const RoomCorrespondence& j,
                    const MatcherConfig& config) {
  const RoomErrors e = RoomPairErrors(i, j, config, true);
  return Within(e.yaw, config.yaw_tolerance_deg * kDegToRad) &&
         Within(e.centre, e.centre_tolerance);
}

}  // namespace matching
}  // namespace is_graphs
