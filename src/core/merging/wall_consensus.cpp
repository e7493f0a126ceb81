#include "wall_consensus.h"

#include <Eigen/Dense>
#include <cmath>

namespace is_graphs {
namespace merging {
namespace detail {

Eigen::Isometry3d ConsensusCorrection(const std::vector<SeenSurface>& surfaces, double offset_scale,
                                      double angle_scale) {
  Eigen::Isometry3d none = Eigen::Isometry3d::Identity();
  if (surfaces.empty()) return none;
  // Rotate about the weighted centre of the surfaces: translation and turn decouple best there.
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  double total = 0.0;
  for (const auto& s : surfaces) c += s.weight * s.at, total += s.weight;
  if (!(total > 0.0)) return none;
  c /= total;
  // x = (tx, ty, theta). A point p of an S-plane moves by t + theta * z x (p - c): the offset
  // along n grows by n . that, the angle by theta.
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int iteration = 0; iteration < 20; ++iteration) {
    Eigen::Matrix3d H = Eigen::Matrix3d::Identity() * 1e-3 * total;  // damping to C = identity
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    for (const auto& s : surfaces) {
      const Eigen::Vector2d r = s.at - c;
      const Eigen::Vector3d j_off(s.normal.x(), s.normal.y(),
                                  s.normal.dot(Eigen::Vector2d(-r.y(), r.x())));
      const Eigen::Vector3d j_ang(0.0, 0.0, 1.0);
      const double e_off = (s.offset + j_off.dot(x)) / offset_scale;
      const double e_ang = (s.angle + x.z()) / angle_scale;
      const double w_off = s.weight / (1.0 + e_off * e_off) / (offset_scale * offset_scale);
      const double w_ang = s.weight / (1.0 + e_ang * e_ang) / (angle_scale * angle_scale);
      H += w_off * j_off * j_off.transpose() + w_ang * j_ang * j_ang.transpose();
      g += w_off * j_off * s.offset + w_ang * j_ang * s.angle;
    }
    const Eigen::Vector3d next = -H.ldlt().solve(g);
    const bool done = (next - x).norm() < 1e-7;
    x = next;
    if (done) break;
  }
  // Rotation theta about c, then t: p -> R (p - c) + c + t.
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(x.z()).toRotationMatrix();
  Eigen::Isometry3d C = Eigen::Isometry3d::Identity();
  C.linear().topLeftCorner<2, 2>() = R;
  C.translation().head<2>() = c - R * c + x.head<2>();
  return C;
}

}  // namespace detail
}  // namespace merging
}  // namespace is_graphs
