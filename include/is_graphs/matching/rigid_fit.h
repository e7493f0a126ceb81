#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "is_graphs/geometry/se3.h"

namespace is_graphs {
namespace matching {

/// A gravity-aligned rigid motion in the plane: p_B = R(yaw) p_M + t. Proper by construction
/// (a rotation angle, never a matrix), so a mirror image can never be "fitted".
struct Pose2 {
  double yaw{0.0};
  Eigen::Vector2d t{Eigen::Vector2d::Zero()};

  Eigen::Matrix2d R() const;
  Eigen::Vector2d Apply(const Eigen::Vector2d& p) const { return R() * p + t; }
  Eigen::Vector2d Rotate(const Eigen::Vector2d& v) const { return R() * v; }
  /// As an SE(3) rotation about z plus translation (z translation 0).
  Eigen::Isometry3d ToIsometry() const;
};

/// |a - b| wrapped to [0, π] (inline: candidate generation and growth call it per pair).
inline double AngleDistance(double a, double b) {
  return std::abs(geometry::NormalizeAngle(a - b));
}

/// An S-plane (normal n_s, n_s·p = d_s, in M) matched to an A-surface (n_a, d_a, in B). The
/// residual is compared at `a_ref` (the A-room centre): the distance of a_ref in front of the
/// moved S-plane minus its distance in front of the A-surface.
struct PlaneCorrespondence {
  Eigen::Vector2d s_normal{Eigen::Vector2d::UnitX()};
  double s_d{0.0};
  Eigen::Vector2d a_normal{Eigen::Vector2d::UnitX()};
  double a_d{0.0};
  Eigen::Vector2d a_ref{Eigen::Vector2d::Zero()};
};

/// A point in M matched to a point in B (room centres), with an isotropic standard deviation.
struct PointCorrespondence {
  Eigen::Vector2d s_point{Eigen::Vector2d::Zero()};
  Eigen::Vector2d a_point{Eigen::Vector2d::Zero()};
  double sigma{0.3};
};

struct RigidFitWeights {
  double normal_sigma_rad{0.02};  // of a plane normal's direction
  double offset_sigma{0.05};      // of a plane offset [m]
};

struct RigidFit {
  Pose2 pose;
  Eigen::Matrix2d t_information{Eigen::Matrix2d::Zero()};
  bool translation_determined{false};        // two non-parallel plane directions or a point prior
  bool planes_determine_translation{false};  // the planes alone fix t (not only a prior)
};

/// Least squares of yaw and translation: the yaw from plane normals and from the room-centre
/// displacements about their weighted centroid (2-D Kabsch with the rotation angle as the
/// unknown, hence never a reflection), then the translation from plane offsets (and points).
RigidFit FitYawTranslation(const std::vector<PlaneCorrespondence>& planes,
                           const std::vector<PointCorrespondence>& points,
                           const RigidFitWeights& weights = {});

/// Residual of one plane correspondence under `pose` (see PlaneCorrespondence).
double PlaneResidual(const PlaneCorrespondence& c, const Pose2& pose);

}  // namespace matching
}  // namespace is_graphs
