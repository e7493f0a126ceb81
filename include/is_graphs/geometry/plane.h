#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <optional>
#include <string>

namespace is_graphs {
namespace geometry {

/// A plane {p : normal · p = d} with a unit normal.
///
/// Its closest-point form is Π = d · normal, the point of the plane nearest the origin. The pair
/// (normal, d) is kept rather than Π alone because Π loses the normal when the plane passes
/// through the origin.
struct Plane {
  Eigen::Vector3d normal{Eigen::Vector3d::UnitX()};
  double d{0.0};

  Plane() = default;
  /// {p : n · p = offset}; n need not be unit (both are divided by |n|). A zero n gives the
  /// default plane x = 0.
  Plane(const Eigen::Vector3d& n, double offset);

  /// Plane through `point` with normal `n` (normalized here).
  static Plane FromPointNormal(const Eigen::Vector3d& point, const Eigen::Vector3d& n);
  /// From the closest-point form Π; requires |Π| > 0 (Π = 0 gives the default plane x = 0, as the
  /// normal is lost: this is why the pair (normal, d) is stored).
  static Plane FromClosestPoint(const Eigen::Vector3d& closest_point);

  Eigen::Vector3d ClosestPoint() const { return d * normal; }
  /// Signed distance of p (positive on the side the normal points to).
  double SignedDistance(const Eigen::Vector3d& p) const { return normal.dot(p) - d; }
  /// Orthogonal projection of p onto the plane.
  Eigen::Vector3d Project(const Eigen::Vector3d& p) const { return p - SignedDistance(p) * normal; }
  /// The same plane with the opposite normal.
  Plane Flipped() const { return Plane(-normal, -d); }
  /// This plane (given in frame A) expressed in frame B, for b_T_a mapping A points to B.
  Plane Transformed(const Eigen::Isometry3d& b_T_a) const;
};

/// Horizontal orientation class of a vertical plane, as in S-Graphs.
enum class Orientation { kX = 0, kY = 1, kOther = 2, kHorizontal = 3 };

/// kX when |n_x| ≥ cos(tolerance), kY when |n_y| ≥ cos(tolerance), kHorizontal when
/// |n_z| ≥ cos(tolerance), else kOther.
Orientation ClassifyOrientation(const Eigen::Vector3d& normal,
                                double tolerance_rad = 10.0 * M_PI / 180.0);

/// "x", "y", "other", "horizontal": the strings of the A-Graph file's `orientation`.
const char* ToString(Orientation orientation);
/// Inverse of ToString; nullopt for any other string.
std::optional<Orientation> OrientationFromString(const std::string& text);

/// Orthonormal basis [b1 b2] of the plane tangent to the unit sphere at n (3x2): b1 = n × e_k /
/// |·| with k the axis of n's smallest component, b2 = n × b1. Every plane residual and
/// information of the project uses this one construction (the S-Graph's informations are on
/// (Bᵀ δn, δd)).
Eigen::Matrix<double, 3, 2> TangentBasis(const Eigen::Vector3d& n);

}  // namespace geometry
}  // namespace is_graphs
