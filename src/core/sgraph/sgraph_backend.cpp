#include "is_graphs/sgraph/sgraph_backend.h"

#include <ceres/loss_function.h>
#include <ceres/manifold.h>
#include <ceres/sphere_manifold.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include <Eigen/Cholesky>
#include <map>
#include <memory>

#include "is_graphs/sgraph/cost/corridor_plane_cost.h"
#include "is_graphs/sgraph/cost/floor_room_cost.h"
#include "is_graphs/sgraph/cost/keyframe_plane_cost.h"
#include "is_graphs/sgraph/cost/odometry_cost.h"
#include "is_graphs/sgraph/cost/room_plane_cost.h"
#include "is_graphs/sgraph/plane_fit.h"

namespace is_graphs {
namespace sgraph {
namespace {

/// Upper-triangular S with SᵀS = information (a tiny ridge keeps semidefinite ones usable).
template <int N>
Eigen::Matrix<double, N, N> SqrtInformation(const Eigen::Matrix<double, N, N>& information) {
  using M = Eigen::Matrix<double, N, N>;
  const M sym = 0.5 * (information + information.transpose()) + 1e-9 * M::Identity();
  const Eigen::LLT<M> llt(sym);
  if (llt.info() != Eigen::Success) return M::Identity();
  return llt.matrixU();
}

struct PoseBlock {
  Eigen::Vector3d t;
  Eigen::Quaterniond q;
};

struct PlaneBlock {
  Eigen::Vector3d n;
  double d;
};

}  // namespace

BackendSummary OptimizeSGraph(BackendProblem& problem, const BackendConfig& config) {
  BackendSummary summary;
  summary.num_keyframes = static_cast<int>(problem.keyframes.size());
  if (problem.keyframes.empty()) {
    summary.message = "no keyframes";
    return summary;
  }
  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem ceres_problem(problem_options);
  ceres::EigenQuaternionManifold quaternion_manifold;
  ceres::SphereManifold<3> sphere_manifold;

  std::map<int, PoseBlock> poses;
  for (const auto& k : problem.keyframes) {
    PoseBlock& b = poses[k.id];
    b.t = k.pose.translation();
    b.q = Eigen::Quaterniond(k.pose.linear()).normalized();
    ceres_problem.AddParameterBlock(b.t.data(), 3);
    ceres_problem.AddParameterBlock(b.q.coeffs().data(), 4, &quaternion_manifold);
  }
  {
    PoseBlock& first = poses.at(problem.keyframes.front().id);
    ceres_problem.SetParameterBlockConstant(first.t.data());
    ceres_problem.SetParameterBlockConstant(first.q.coeffs().data());
  }
  for (const auto& k : problem.keyframes) {
    if (k.previous < 0 || !poses.count(k.previous)) continue;
    PoseBlock& a = poses.at(k.previous);
    PoseBlock& b = poses.at(k.id);
    ceres_problem.AddResidualBlock(
        OdometryCost::Create(k.relative_odom, SqrtInformation<6>(k.odom_information)), nullptr,
        a.t.data(), a.q.coeffs().data(), b.t.data(), b.q.coeffs().data());
  }

  std::map<int, PlaneBlock> planes;
  for (const auto& p : problem.planes) planes[p.id] = {p.plane.normal, p.plane.d};
  std::map<int, bool> plane_used;
  for (const auto& o : problem.observations) {
    auto kf = poses.find(o.keyframe);
    auto pl = planes.find(o.plane);
    if (kf == poses.end() || pl == planes.end()) continue;
    auto* cost = KeyframePlaneCost::Create(o.local, TangentBasis(o.local.normal),
                                           SqrtInformation<3>(o.information));
    ceres_problem.AddResidualBlock(cost, new ceres::HuberLoss(config.plane_huber),
                                   kf->second.t.data(), kf->second.q.coeffs().data(),
                                   pl->second.n.data(), &pl->second.d);
    plane_used[o.plane] = true;
  }
  for (auto& [id, block] : planes)
    if (plane_used.count(id)) ceres_problem.SetManifold(block.n.data(), &sphere_manifold);

  std::map<int, Eigen::Vector2d> centers;
  for (const auto& r : problem.rooms) {
    Eigen::Vector2d& c = centers[r.id];
    c = r.center;
    for (size_t i = 0; i < r.planes.size() && i < r.distances.size(); ++i) {
      auto pl = planes.find(r.planes[i]);
      if (pl == planes.end() || !plane_used.count(r.planes[i])) continue;
      ceres::CostFunction* cost =
          r.type == RoomType::kCorridor
              ? CorridorPlaneCost::Create(r.distances[i], r.z, r.axis, r.initial_center,
                                          config.room_sigma, config.corridor_along_sigma)
              : RoomPlaneCost::Create(r.distances[i], r.z, config.room_sigma);
      ceres_problem.AddResidualBlock(cost, new ceres::CauchyLoss(config.room_cauchy), c.data(),
                                     pl->second.n.data(), &pl->second.d);
    }
    if (!ceres_problem.HasParameterBlock(c.data())) centers.erase(r.id);
  }
  Eigen::Vector2d floor_center = problem.floor.center;
  if (problem.floor.present) {
    for (size_t i = 0; i < problem.floor.rooms.size() && i < problem.floor.offsets.size(); ++i) {
      auto c = centers.find(problem.floor.rooms[i]);
      if (c == centers.end()) continue;
      ceres_problem.AddResidualBlock(
          FloorRoomCost::Create(problem.floor.offsets[i], config.floor_sigma), nullptr,
          floor_center.data(), c->second.data());
    }
  }

  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  options.max_num_iterations = config.max_iterations;
  options.max_solver_time_in_seconds = config.max_solver_time;
  options.num_threads = config.num_threads;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary ceres_summary;
  ceres::Solve(options, &ceres_problem, &ceres_summary);

  summary.usable = ceres_summary.IsSolutionUsable();
  summary.initial_cost = ceres_summary.initial_cost;
  summary.final_cost = ceres_summary.final_cost;
  summary.iterations = static_cast<int>(ceres_summary.iterations.size());
  summary.seconds = ceres_summary.total_time_in_seconds;
  summary.num_residual_blocks = ceres_summary.num_residual_blocks;
  summary.message = ceres_summary.message;
  if (!summary.usable) return summary;

  for (auto& k : problem.keyframes) {
    const PoseBlock& b = poses.at(k.id);
    k.pose = Eigen::Isometry3d::Identity();
    k.pose.linear() = b.q.normalized().toRotationMatrix();
    k.pose.translation() = b.t;
  }
  for (auto& p : problem.planes) {
    const PlaneBlock& b = planes.at(p.id);
    p.plane = geometry::Plane(b.n, b.d);
  }
  for (auto& r : problem.rooms) {
    auto c = centers.find(r.id);
    if (c != centers.end()) r.center = c->second;
  }
  problem.floor.center = floor_center;
  return summary;
}

}  // namespace sgraph
}  // namespace is_graphs
