#include "is_graphs/matching/rigid_fit.h"

#include <cmath>

#include "is_graphs/geometry/se3.h"

namespace is_graphs {
namespace matching {
namespace {

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// The eigenvalues of a symmetric 2×2, ascending, in closed form (Eigen's direct solver also
/// made the eigenvectors, which only the rank-deficient branches need: a tenth of a match).
Eigen::Vector2d Eigenvalues(const Eigen::Matrix2d& m) {
  const double mean = 0.5 * (m(0, 0) + m(1, 1)), half_diff = 0.5 * (m(0, 0) - m(1, 1));
  const double radius = std::sqrt(half_diff * half_diff + m(0, 1) * m(0, 1));
  return {mean - radius, mean + radius};
}

/// The unit eigenvector of a symmetric 2×2's larger eigenvalue.
Eigen::Vector2d MajorAxis(const Eigen::Matrix2d& m) {
  const double angle = 0.5 * std::atan2(2.0 * m(0, 1), m(0, 0) - m(1, 1));
  return {std::cos(angle), std::sin(angle)};
}

}  // namespace

Eigen::Matrix2d Pose2::R() const {
  const double c = std::cos(yaw), s = std::sin(yaw);
  Eigen::Matrix2d r;
  r << c, -s, s, c;
  return r;
}

Eigen::Isometry3d Pose2::ToIsometry() const {
  return geometry::IsometryFromXYYaw(t.x(), t.y(), geometry::NormalizeAngle(yaw));
}

double PlaneResidual(const PlaneCorrespondence& c, const Pose2& pose) {
  const Eigen::Vector2d n = pose.Rotate(c.s_normal);
  const double d = c.s_d + n.dot(pose.t);
  return (n.dot(c.a_ref) - d) - (c.a_normal.dot(c.a_ref) - c.a_d);
}

RigidFit FitYawTranslation(const std::vector<PlaneCorrespondence>& planes,
                           const std::vector<PointCorrespondence>& points,
                           const RigidFitWeights& weights) {
  RigidFit fit;
  // Yaw: maximize Σ w (R a)·b over normal pairs and centred point pairs.
  double sin_sum = 0.0, cos_sum = 0.0;
  const double wn = 1.0 / (weights.normal_sigma_rad * weights.normal_sigma_rad);
  for (const auto& c : planes) {
    sin_sum += wn * Cross(c.s_normal, c.a_normal);
    cos_sum += wn * c.s_normal.dot(c.a_normal);
  }
  if (points.size() >= 2) {
    Eigen::Vector2d ms = Eigen::Vector2d::Zero(), ma = Eigen::Vector2d::Zero();
    double wsum = 0.0;
    for (const auto& p : points) {
      const double w = 1.0 / (p.sigma * p.sigma);
      ms += w * p.s_point;
      ma += w * p.a_point;
      wsum += w;
    }
    ms /= wsum;
    ma /= wsum;
    for (const auto& p : points) {
      const double w = 1.0 / (p.sigma * p.sigma);
      sin_sum += w * Cross(p.s_point - ms, p.a_point - ma);
      cos_sum += w * (p.s_point - ms).dot(p.a_point - ma);
    }
  }
  fit.pose.yaw = (sin_sum == 0.0 && cos_sum == 0.0) ? 0.0 : std::atan2(sin_sum, cos_sum);
  // The rotation straight from the sums (no sin/cos of the angle just taken).
  const double norm = std::hypot(sin_sum, cos_sum);
  const double c = norm > 0.0 ? cos_sum / norm : 1.0, s = norm > 0.0 ? sin_sum / norm : 0.0;
  Eigen::Matrix2d r;
  r << c, -s, s, c;

  // Translation: Σ wo (n'·t - y)² + Σ wp |a - R s - t|².
  Eigen::Matrix2d a = Eigen::Matrix2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  const double wo = 1.0 / (weights.offset_sigma * weights.offset_sigma);
  for (const auto& c : planes) {
    const Eigen::Vector2d n = r * c.s_normal;
    const double y = n.dot(c.a_ref) - c.s_d - (c.a_normal.dot(c.a_ref) - c.a_d);
    a += wo * n * n.transpose();
    b += wo * n * y;
  }
  const Eigen::Vector2d plane_only = Eigenvalues(a);
  fit.planes_determine_translation =
      planes.size() >= 2 && plane_only(0) > 0.05 * wo;  // normals >~ 13° apart
  if (!fit.planes_determine_translation && a.trace() > 0.0) {
    // Nearly parallel planes: keep only the direction they fix (the other, ill-conditioned by
    // the noise between their normals, is left to the points).
    const Eigen::Vector2d v = MajorAxis(a);
    a = plane_only(1) * v * v.transpose();
    b = v * v.dot(b);
  }
  for (const auto& p : points) {
    const double w = 1.0 / (p.sigma * p.sigma);
    a += w * Eigen::Matrix2d::Identity();
    b += w * (p.a_point - r * p.s_point);
  }
  const Eigen::Vector2d eigenvalues = Eigenvalues(a);
  fit.translation_determined = eigenvalues(0) > 1e-9;
  if (fit.translation_determined) {
    fit.pose.t = a.ldlt().solve(b);
  } else if (a.trace() > 0.0) {
    // Rank one (parallel planes, no point): the minimum-norm solution along the known direction.
    const Eigen::Vector2d dir = MajorAxis(a);
    fit.pose.t = dir * (dir.dot(b) / eigenvalues(1));
  }
  fit.t_information = a;
  return fit;
}

}  // namespace matching
}  // namespace is_graphs
