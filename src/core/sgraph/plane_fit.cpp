#include "is_graphs/sgraph/plane_fit.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <optional>

namespace is_graphs {
namespace sgraph {

std::optional<PlaneFit> FitPlane(const PointList& points, const std::vector<int>& indices,
                                 double point_sigma, int max_effective_points,
                                 const std::optional<Eigen::Vector3d>& vertical_about) {
  const int n_points = static_cast<int>(indices.size());
  if (n_points < 3) return std::nullopt;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int i : indices) mean += points[i].cast<double>();
  mean /= n_points;
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (int i : indices) {
    const Eigen::Vector3d q = points[i].cast<double>() - mean;
    scatter += q * q.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  const Eigen::Vector3d values = eig.eigenvalues();                           // ascending
  if (!(values(1) > 1e-9 * std::max(values(2), 1e-12))) return std::nullopt;  // collinear
  PlaneFit fit;
  Eigen::Vector3d normal = eig.eigenvectors().col(0).normalized();
  if (vertical_about && vertical_about->norm() > 1e-9) {
    // The scatter of the horizontal projection; the up direction gets the largest eigenvalue.
    const Eigen::Vector3d up = vertical_about->normalized();
    const Eigen::Matrix3d p = Eigen::Matrix3d::Identity() - up * up.transpose();
    const Eigen::Matrix3d horizontal = p * scatter * p + (values(2) + 1.0) * up * up.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig_h(horizontal);
    if (!(eig_h.eigenvalues()(1) > 1e-9 * std::max(values(2), 1e-12))) return std::nullopt;
    normal = eig_h.eigenvectors().col(0).normalized();
  }
  fit.plane = geometry::Plane(normal, normal.dot(mean));
  fit.centroid = mean;
  // H = Σ J_iᵀ J_i / σ², J_i = [p_iᵀ B, −1]; computed from the moments about the origin.
  const Eigen::Matrix<double, 3, 2> basis = TangentBasis(fit.plane.normal);
  Eigen::Matrix4d moments = Eigen::Matrix4d::Zero();  // Σ [p; −1][p; −1]ᵀ
  moments.topLeftCorner<3, 3>() = scatter + n_points * mean * mean.transpose();
  moments.topRightCorner<3, 1>() = -n_points * mean;
  moments.bottomLeftCorner<1, 3>() = -n_points * mean.transpose();
  moments(3, 3) = n_points;
  Eigen::Matrix<double, 4, 3> g = Eigen::Matrix<double, 4, 3>::Zero();
  g.topLeftCorner<3, 2>() = basis;
  g(3, 2) = 1.0;
  const double scale = std::min(1.0, static_cast<double>(max_effective_points) / n_points) /
                       (point_sigma * point_sigma);
  fit.information = scale * g.transpose() * moments * g;
  fit.covariance = CovarianceFromInformation(fit.plane.normal, fit.information);
  return fit;
}

Eigen::Matrix4d CovarianceFromInformation(const Eigen::Vector3d& n,
                                          const Eigen::Matrix3d& information) {
  Eigen::Matrix<double, 4, 3> g = Eigen::Matrix<double, 4, 3>::Zero();
  g.topLeftCorner<3, 2>() = TangentBasis(n);
  g(3, 2) = 1.0;
  const Eigen::Matrix3d cov =
      (information + 1e-12 * Eigen::Matrix3d::Identity()).ldlt().solve(Eigen::Matrix3d::Identity());
  return g * cov * g.transpose();
}

Eigen::Matrix3d TangentCovariance(const Eigen::Vector3d& n, const Eigen::Matrix4d& covariance) {
  Eigen::Matrix<double, 4, 3> g = Eigen::Matrix<double, 4, 3>::Zero();
  g.topLeftCorner<3, 2>() = TangentBasis(n);
  g(3, 2) = 1.0;
  return g.transpose() * covariance * g;
}

Eigen::Matrix4d TransformPlaneCovariance(const geometry::Plane& /*plane_a*/,
                                         const Eigen::Matrix4d& covariance_a,
                                         const Eigen::Isometry3d& b_T_a) {
  // n_b = R n_a, d_b = d_a + (R n_a)·t: linear in (n_a, d_a).
  Eigen::Matrix4d a = Eigen::Matrix4d::Zero();
  const Eigen::Matrix3d r = b_T_a.linear();
  a.topLeftCorner<3, 3>() = r;
  a.bottomLeftCorner<1, 3>() = (r.transpose() * b_T_a.translation()).transpose();
  a(3, 3) = 1.0;
  return a * covariance_a * a.transpose();
}

}  // namespace sgraph
}  // namespace is_graphs
