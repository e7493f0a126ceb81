#pragma once

#include <Eigen/Core>

namespace is_graphs {
namespace agraph {

/// The wall centre of docs/agraph_format.md, for the planes {p : n_i · p = d_i}: the wall point
/// w_s is projected onto each surface, q_i = w_s − (n_i · w_s − d_i) n_i, and c = (q_a + q_b) / 2.
/// For an x-wall (n_a = +x̂, n_b = −x̂) this is c = ((d_a − d_b) / 2, w_s,y, w_s,z).
/// Finite for any planes (also non-parallel ones). Templated for ceres::Jet; the normals are
/// used as given (unit normals expected).
template <typename T>
Eigen::Matrix<T, 3, 1> WallCentre(const Eigen::Matrix<T, 3, 1>& n_a, const T& d_a,
                                  const Eigen::Matrix<T, 3, 1>& n_b, const T& d_b,
                                  const Eigen::Matrix<T, 3, 1>& w_s) {
  const Eigen::Matrix<T, 3, 1> q_a = w_s - (n_a.dot(w_s) - d_a) * n_a;
  const Eigen::Matrix<T, 3, 1> q_b = w_s - (n_b.dot(w_s) - d_b) * n_b;
  return T(0.5) * (q_a + q_b);
}

}  // namespace agraph
}  // namespace is_graphs
