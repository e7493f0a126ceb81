#include "is_graphs/geometry/plane.h"

namespace is_graphs {
namespace geometry {

Plane::Plane(const Eigen::Vector3d& n, double offset) {
  const double norm = n.norm();
  if (norm > 0.0 && std::isfinite(norm)) {
    normal = n / norm;
    d = offset / norm;
  }
}

Plane Plane::FromPointNormal(const Eigen::Vector3d& point, const Eigen::Vector3d& n) {
  const double norm = n.norm();
  if (!(norm > 0.0)) return Plane();
  const Eigen::Vector3d unit = n / norm;
  return Plane(unit, unit.dot(point));
}

Plane Plane::FromClosestPoint(const Eigen::Vector3d& closest_point) {
  const double distance = closest_point.norm();
  if (!(distance > 0.0)) return Plane();
  return Plane(closest_point / distance, distance);
}

Plane Plane::Transformed(const Eigen::Isometry3d& b_T_a) const {
  // A point p_a = d n_a of the plane maps to p_b = R p_a + t on the plane with normal n_b = R n_a,
  // so d_b = n_b · p_b = d + n_b · t.
  const Eigen::Vector3d normal_b = b_T_a.linear() * normal;
  return Plane(normal_b, d + normal_b.dot(b_T_a.translation()));
}

Orientation ClassifyOrientation(const Eigen::Vector3d& normal, double tolerance_rad) {
  const double norm = normal.norm();
  if (!(norm > 0.0)) return Orientation::kOther;
  const Eigen::Vector3d n = normal.cwiseAbs() / norm;
  const double threshold = std::cos(tolerance_rad);
  if (n.x() >= threshold) return Orientation::kX;
  if (n.y() >= threshold) return Orientation::kY;
  if (n.z() >= threshold) return Orientation::kHorizontal;
  return Orientation::kOther;
}

const char* ToString(Orientation orientation) {
  switch (orientation) {
    case Orientation::kX:
      return "x";
    case Orientation::kY:
      return "y";
    case Orientation::kOther:
      return "other";
    case Orientation::kHorizontal:
      return "horizontal";
  }
  return "other";
}

std::optional<Orientation> OrientationFromString(const std::string& text) {
  for (Orientation o :
       {Orientation::kX, Orientation::kY, Orientation::kOther, Orientation::kHorizontal}) {
    if (text == ToString(o)) return o;
  }
  return std::nullopt;
}

Eigen::Matrix<double, 3, 2> TangentBasis(const Eigen::Vector3d& n) {
  Eigen::Index axis = 0;
  n.cwiseAbs().minCoeff(&axis);
  const Eigen::Vector3d b1 = n.cross(Eigen::Vector3d::Unit(axis)).normalized();
  Eigen::Matrix<double, 3, 2> basis;
  basis.col(0) = b1;
  basis.col(1) = n.cross(b1).normalized();
  return basis;
}

}  // namespace geometry
}  // namespace is_graphs
