#pragma once

// The one place that knows which Ceres it is built against (1.14 to 2.2).
//
// Ceres 2.1 replaced LocalParameterization by Manifold and 2.2 removed the former; 1.14 (Ubuntu
// 20.04, Debian 11) and 2.0 (Ubuntu 22.04) have only LocalParameterization. The project needs two
// parameterizations, on both APIs the same maps:
//   - the unit sphere S² for plane normals: Ceres' SphereManifold<3> (2.1+) and
//     HomogeneousVectorParameterization(3) (older): a Householder-based Plus on a 2-D tangent
//     space that turns x by kUnitSphereTurnPerStep · |δ| (Ceres 2.2 doubled it: the same
//     directions, a tangent scaled by 2, which Ceres' Jacobian scaling makes immaterial to the
//     minimizer);
//   - the unit quaternion in Eigen's (x, y, z, w) order: EigenQuaternionManifold (2.1+) and
//     EigenQuaternionParameterization (older), q ⊞ δ = [δ/|δ| sin|δ|, cos|δ|] ⊗ q (a rotation
//     by 2|δ| about δ), a 3-D tangent space.
// Everything else the project uses of Ceres is the same in 1.14 and 2.2.

#include <ceres/problem.h>
#include <ceres/version.h>

#if CERES_VERSION_MAJOR > 2 || (CERES_VERSION_MAJOR == 2 && CERES_VERSION_MINOR >= 1)
#define IS_GRAPHS_CERES_HAS_MANIFOLD 1
#include <ceres/manifold.h>
#include <ceres/sphere_manifold.h>
#else
#define IS_GRAPHS_CERES_HAS_MANIFOLD 0
#include <ceres/local_parameterization.h>
#endif

namespace is_graphs {
namespace ceres_compat {

/// The angle (rad) the unit-sphere Plus turns x by per unit of |δ|: 1/2 up to Ceres 2.1, 1 from
/// 2.2 on (SphereManifold's step changed there).
#if CERES_VERSION_MAJOR > 2 || (CERES_VERSION_MAJOR == 2 && CERES_VERSION_MINOR >= 2)
constexpr double kUnitSphereTurnPerStep = 1.0;
#else
constexpr double kUnitSphereTurnPerStep = 0.5;
#endif

#if IS_GRAPHS_CERES_HAS_MANIFOLD
/// What ceres::Problem::AddParameterBlock takes as a block's parameterization.
using Parameterization = ceres::Manifold;

/// A new unit-sphere parameterization of a 3-vector (the caller or a Problem owns it).
inline Parameterization* NewUnitSphere3() { return new ceres::SphereManifold<3>(); }
/// A new unit-quaternion parameterization of an Eigen::Quaterniond's coeffs() (x, y, z, w).
inline Parameterization* NewEigenQuaternion() { return new ceres::EigenQuaternionManifold(); }

inline void SetParameterization(ceres::Problem& problem, double* block, Parameterization* p) {
  problem.SetManifold(block, p);
}
inline const Parameterization* GetParameterization(const ceres::Problem& problem,
                                                   const double* block) {
  return problem.GetManifold(block);
}
/// The dimension of the block's tangent (local) space.
inline int TangentSize(const ceres::Problem& problem, const double* block) {
  return problem.ParameterBlockTangentSize(block);
}
/// x ⊞ δ through the parameterization.
inline bool Plus(const Parameterization& p, const double* x, const double* delta,
                 double* x_plus_delta) {
  return p.Plus(x, delta, x_plus_delta);
}
/// The ambient-by-tangent Jacobian of x ⊞ δ at δ = 0, row-major.
inline bool PlusJacobian(const Parameterization& p, const double* x, double* jacobian) {
  return p.PlusJacobian(x, jacobian);
}
inline int AmbientSize(const Parameterization& p) { return p.AmbientSize(); }
inline int TangentSize(const Parameterization& p) { return p.TangentSize(); }
#else
using Parameterization = ceres::LocalParameterization;

inline Parameterization* NewUnitSphere3() {
  return new ceres::HomogeneousVectorParameterization(3);
}
inline Parameterization* NewEigenQuaternion() {
  return new ceres::EigenQuaternionParameterization();
}

inline void SetParameterization(ceres::Problem& problem, double* block, Parameterization* p) {
  problem.SetParameterization(block, p);
}
inline const Parameterization* GetParameterization(const ceres::Problem& problem,
                                                   const double* block) {
  return problem.GetParameterization(const_cast<double*>(block));
}
inline int TangentSize(const ceres::Problem& problem, const double* block) {
  return problem.ParameterBlockLocalSize(block);
}
inline bool Plus(const Parameterization& p, const double* x, const double* delta,
                 double* x_plus_delta) {
  return p.Plus(x, delta, x_plus_delta);
}
inline bool PlusJacobian(const Parameterization& p, const double* x, double* jacobian) {
  return p.ComputeJacobian(x, jacobian);
}
inline int AmbientSize(const Parameterization& p) { return p.GlobalSize(); }
inline int TangentSize(const Parameterization& p) { return p.LocalSize(); }
#endif

}  // namespace ceres_compat
}  // namespace is_graphs
