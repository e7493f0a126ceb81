#pragma once

#include <ceres/autodiff_cost_function.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace is_graphs {
namespace sgraph {

/// Odometry between two keyframes i and j: the relative pose T_i⁻¹ T_j stays at its measured
/// value Z = T_i,odom⁻¹ T_j,odom, whose translation is scaled by the odometry's scale factor s
/// (legged odometry over- or under-reads distance by a few per cent; s is estimated with the
/// graph, under OdometryScalePriorCost):
///
///   Z(s) = (R_Z, s t_Z),  E = Z(s)⁻¹ (T_i⁻¹ T_j),  residual (6) = Σ^{-1/2} [ t_E ; 2 vec(q_E) ]
///
/// in the tangent order (x, y, z, rx, ry, rz) of Keyframe::odom_information (2 vec(q) is the
/// rotation vector for small errors; q_E is taken with w ≥ 0).
///
/// Parameter blocks:
///   t_i  keyframe i position (3)
///   q_i  keyframe i orientation (4), Eigen order (x, y, z, w), on EigenQuaternionManifold
///   t_j  keyframe j position (3)
///   q_j  keyframe j orientation (4)
///   s    odometry scale factor (1), shared by all odometry edges
class OdometryCost {
 public:
  OdometryCost(const Eigen::Isometry3d& measured,
               const Eigen::Matrix<double, 6, 6>& sqrt_information)
      : t_measured_(measured.translation()),
        q_measured_(Eigen::Quaterniond(measured.linear()).normalized()),
        sqrt_information_(sqrt_information) {}

  template <typename T>
  bool operator()(const T* const ti, const T* const qi, const T* const tj, const T* const qj,
                  const T* const scale, T* residual) const {
    using Vector3T = Eigen::Matrix<T, 3, 1>;
    using QuaternionT = Eigen::Quaternion<T>;
    const Eigen::Map<const Vector3T> p_i(ti), p_j(tj);
    const Eigen::Map<const QuaternionT> q_i(qi), q_j(qj);
    const QuaternionT q_i_inv = q_i.conjugate();
    const QuaternionT q_ij = q_i_inv * q_j;
    const Vector3T t_ij = q_i_inv * (p_j - p_i);
    const QuaternionT q_m_inv = q_measured_.conjugate().template cast<T>();
    QuaternionT q_e = q_m_inv * q_ij;
    const Vector3T t_e = q_m_inv * (t_ij - scale[0] * t_measured_.template cast<T>());
    if (q_e.w() < T(0)) q_e.coeffs() = -q_e.coeffs();
    Eigen::Matrix<T, 6, 1> e;
    e.template head<3>() = t_e;
    e.template tail<3>() = T(2.0) * q_e.vec();
    Eigen::Map<Eigen::Matrix<T, 6, 1>> r(residual);
    r = sqrt_information_.template cast<T>() * e;
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Isometry3d& measured,
                                     const Eigen::Matrix<double, 6, 6>& sqrt_information) {
    return new ceres::AutoDiffCostFunction<OdometryCost, 6, 3, 4, 3, 4, 1>(
        new OdometryCost(measured, sqrt_information));
  }

 private:
  Eigen::Vector3d t_measured_;
  Eigen::Quaterniond q_measured_;
  Eigen::Matrix<double, 6, 6> sqrt_information_;
};

}  // namespace sgraph
}  // namespace is_graphs
