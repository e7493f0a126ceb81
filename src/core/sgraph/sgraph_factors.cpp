#include "is_graphs/sgraph/sgraph_factors.h"

#include <ceres/loss_function.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <limits>

#include "is_graphs/common/ceres_compat.h"
#include "is_graphs/sgraph/cost/corridor_plane_cost.h"
#include "is_graphs/sgraph/cost/floor_room_cost.h"
#include "is_graphs/sgraph/cost/keyframe_plane_cost.h"
#include "is_graphs/sgraph/cost/odometry_cost.h"
#include "is_graphs/sgraph/cost/odometry_scale_prior_cost.h"
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

}  // namespace

SGraphFactors::SGraphFactors(const BackendProblem& problem) {
  for (const auto& k : problem.keyframes)
    poses[k.id] = {k.pose.translation(), Eigen::Quaterniond(k.pose.linear()).normalized()};
  for (const auto& p : problem.planes) planes[p.id] = {p.plane.normal, p.plane.d, false};
  for (const auto& r : problem.rooms) centres[r.id] = r.center;
  floor_centre = problem.floor.center;
  odometry_scale = problem.odometry_scale;
}

void SGraphFactors::AddTo(const BackendProblem& problem, const BackendConfig& config,
                          ceres::Problem& ceres_problem) {
  auto* quaternion = ceres_compat::NewEigenQuaternion();  // owned by ceres_problem
  for (const auto& k : problem.keyframes) {
    PoseBlock& b = poses.at(k.id);
    ceres_problem.AddParameterBlock(b.t.data(), 3);
    ceres_problem.AddParameterBlock(b.q.coeffs().data(), 4, quaternion);
  }
  auto hold = [&](const Keyframe& k) {
    PoseBlock& b = poses.at(k.id);
    ceres_problem.SetParameterBlockConstant(b.t.data());
    ceres_problem.SetParameterBlockConstant(b.q.coeffs().data());
  };
  if (!problem.keyframes.empty()) hold(problem.keyframes.front());
  const auto& held = problem.constant_keyframes;  // windowed (backend_window.h)
  for (const auto& k : problem.keyframes)
    if (held.count(k.id)) hold(k);
  for (const auto& k : problem.keyframes) {
    if (k.previous < 0 || !poses.count(k.previous)) continue;
    if (held.count(k.id) && held.count(k.previous)) continue;  // nothing to move
    PoseBlock& a = poses.at(k.previous);
    PoseBlock& b = poses.at(k.id);
    ceres_problem.AddResidualBlock(
        OdometryCost::Create(k.relative_odom, SqrtInformation<6>(k.odom_information)), nullptr,
        a.t.data(), a.q.coeffs().data(), b.t.data(), b.q.coeffs().data(), &odometry_scale);
  }
  if (ceres_problem.HasParameterBlock(&odometry_scale)) {
    if (config.odometry_scale_sigma > 0.0) {
      ceres_problem.AddResidualBlock(OdometryScalePriorCost::Create(config.odometry_scale_sigma),
                                     nullptr, &odometry_scale);
      odometry_scale = std::clamp(odometry_scale, 1.0 - config.odometry_scale_max_error,
                                  1.0 + config.odometry_scale_max_error);
      ceres_problem.SetParameterLowerBound(&odometry_scale, 0,
                                           1.0 - config.odometry_scale_max_error);
      ceres_problem.SetParameterUpperBound(&odometry_scale, 0,
                                           1.0 + config.odometry_scale_max_error);
    } else {
      ceres_problem.SetParameterBlockConstant(&odometry_scale);
    }
  }
  for (const auto& o : problem.observations) {
    auto kf = poses.find(o.keyframe);
    auto pl = planes.find(o.plane);
    if (kf == poses.end() || pl == planes.end()) continue;
    ceres_problem.AddResidualBlock(KeyframePlaneCost::Create(o.local, TangentBasis(o.local.normal),
                                                             SqrtInformation<3>(o.information)),
                                   new ceres::HuberLoss(config.plane_huber), kf->second.t.data(),
                                   kf->second.q.coeffs().data(), pl->second.n.data(),
                                   &pl->second.d);
    pl->second.observed = true;
  }
  auto* sphere = ceres_compat::NewUnitSphere3();  // owned by ceres_problem
  for (auto& [id, block] : planes)
    if (block.observed) ceres_compat::SetParameterization(ceres_problem, block.n.data(), sphere);

  // Planes held in a windowed problem: a moved room's planes that the window does not see.
  for (int id : problem.constant_planes) {
    auto pl = planes.find(id);
    if (pl == planes.end() || pl->second.observed) continue;
    for (double* b : {pl->second.n.data(), &pl->second.d}) {
      ceres_problem.AddParameterBlock(b, b == &pl->second.d ? 1 : 3);
      ceres_problem.SetParameterBlockConstant(b);
    }
  }
  for (const auto& r : problem.rooms) {
    if (problem.constant_rooms.count(r.id)) continue;
    Eigen::Vector2d& c = centres.at(r.id);
    for (size_t i = 0; i < r.planes.size() && i < r.distances.size(); ++i) {
      auto pl = planes.find(r.planes[i]);
      if (pl == planes.end() || !ceres_problem.HasParameterBlock(&pl->second.d)) continue;
      ceres::CostFunction* cost =
          r.type == RoomType::kCorridor
              ? CorridorPlaneCost::Create(r.distances[i], r.z, r.axis, r.initial_center,
                                          config.room_sigma, config.corridor_along_sigma)
              : RoomPlaneCost::Create(r.distances[i], r.z, config.room_sigma);
      ceres_problem.AddResidualBlock(cost, new ceres::CauchyLoss(config.room_cauchy), c.data(),
                                     pl->second.n.data(), &pl->second.d);
    }
  }
  if (!problem.floor.present || problem.constant_floor) return;
  for (size_t i = 0; i < problem.floor.rooms.size() && i < problem.floor.offsets.size(); ++i) {
    auto c = centres.find(problem.floor.rooms[i]);
    if (c == centres.end()) continue;
    if (problem.constant_rooms.count(c->first)) {  // windowed: a room the window does not move
      ceres_problem.AddParameterBlock(c->second.data(), 2);
      ceres_problem.SetParameterBlockConstant(c->second.data());
    }
    if (!ceres_problem.HasParameterBlock(c->second.data())) continue;
    ceres_problem.AddResidualBlock(
        FloorRoomCost::Create(problem.floor.offsets[i], config.floor_sigma), nullptr,
        floor_centre.data(), c->second.data());
  }
}

void SGraphFactors::WriteBack(BackendProblem& problem) const {
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
  for (auto& r : problem.rooms) r.center = centres.at(r.id);
  problem.floor.center = floor_centre;
  problem.odometry_scale = odometry_scale;
}

BackendProblem BackendProblemFromSnapshot(const SGraph& graph) {
  BackendProblem problem;
  problem.keyframes = graph.keyframes;
  problem.planes = graph.planes;
  problem.observations = graph.observations;
  problem.odometry_scale = graph.odometry_scale;
  std::map<int, const Plane*> by_id;
  for (const auto& p : graph.planes) by_id[p.id] = &p;
  for (const auto& r : graph.rooms) {
    BackendRoom b;
    b.id = r.id;
    b.type = r.type;
    b.center = b.initial_center = r.center.head<2>();
    b.z = r.center.z();
    b.planes = r.planes;
    for (int id : r.planes) {
      auto p = by_id.find(id);
      b.distances.push_back(p == by_id.end() ? std::numeric_limits<double>::quiet_NaN()
                                             : p->second->plane.SignedDistance(r.center));
    }
    const Eigen::Vector2d across = CorridorAcross(graph, r);
    b.axis = Eigen::Vector2d(-across.y(), across.x());
    problem.rooms.push_back(b);
  }
  if (!graph.floors.empty()) {
    const Floor& f = graph.floors.front();
    problem.floor.present = true;
    problem.floor.center = f.center.head<2>();
    for (int room_id : f.rooms) {
      for (const auto& r : graph.rooms) {
        if (r.id != room_id) continue;
        problem.floor.rooms.push_back(room_id);
        problem.floor.offsets.push_back(r.center.head<2>() - problem.floor.center);
      }
    }
  }
  return problem;
}

Eigen::Vector2d CorridorAcross(const SGraph& graph, const Room& room) {
  for (int id : room.planes) {
    for (const auto& p : graph.planes) {
      if (p.id != id) continue;
      const Eigen::Vector2d n = p.plane.normal.head<2>();
      if (n.norm() > 0.5) return n.normalized();
    }
  }
  return Eigen::Vector2d::Zero();
}

}  // namespace sgraph
}  // namespace is_graphs
