#include "is_graphs/merging/is_graph_problem.h"

#include <ceres/covariance.h>
#include <ceres/loss_function.h>
#include <ceres/manifold.h>
#include <ceres/problem.h>
#include <ceres/solver.h>
#include <ceres/sphere_manifold.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <memory>
#include <set>

#include "is_graphs/agraph/agraph_problem.h"
#include "is_graphs/geometry/se3.h"
#include "is_graphs/merging/cost/corridor_match_cost.h"
#include "is_graphs/merging/cost/room_match_cost.h"
#include "is_graphs/merging/cost/surface_match_cost.h"
#include "is_graphs/merging/cost/transform_prior_cost.h"
#include "is_graphs/sgraph/cost/corridor_plane_cost.h"
#include "is_graphs/sgraph/cost/floor_room_cost.h"
#include "is_graphs/sgraph/cost/keyframe_plane_cost.h"
#include "is_graphs/sgraph/cost/odometry_cost.h"
#include "is_graphs/sgraph/cost/room_plane_cost.h"
#include "is_graphs/sgraph/plane_fit.h"

namespace is_graphs {
namespace merging {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

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
  bool observed{false};
};

// The S-Graph side of the problem: blocks at the snapshot's values, and (optionally) its factors.
struct SGraphBlocks {
  std::map<int, PoseBlock> poses;
  std::map<int, PlaneBlock> planes;
  std::map<int, Eigen::Vector2d> centres;
  Eigen::Vector2d floor_centre{Eigen::Vector2d::Zero()};

  void Build(const sgraph::SGraph& g, const MergerConfig& config, ceres::Problem& problem) {
    for (const auto& p : g.planes) planes[p.id] = {p.plane.normal, p.plane.d};
    for (const auto& r : g.rooms) centres[r.id] = r.center.head<2>();
    if (!config.optimize_sgraph) return;
    const auto& sc = config.sgraph;
    auto* quaternion = new ceres::EigenQuaternionManifold;  // owned by the problem
    for (const auto& k : g.keyframes) {
      PoseBlock& b = poses[k.id];
      b.t = k.pose.translation();
      b.q = Eigen::Quaterniond(k.pose.linear()).normalized();
      problem.AddParameterBlock(b.t.data(), 3);
      problem.AddParameterBlock(b.q.coeffs().data(), 4, quaternion);
    }
    if (!g.keyframes.empty()) {  // the gauge of M
      PoseBlock& first = poses.at(g.keyframes.front().id);
      problem.SetParameterBlockConstant(first.t.data());
      problem.SetParameterBlockConstant(first.q.coeffs().data());
    }
    for (const auto& k : g.keyframes) {
      if (k.previous < 0 || !poses.count(k.previous)) continue;
      PoseBlock& a = poses.at(k.previous);
      PoseBlock& b = poses.at(k.id);
      problem.AddResidualBlock(
          sgraph::OdometryCost::Create(k.relative_odom, SqrtInformation<6>(k.odom_information)),
          nullptr, a.t.data(), a.q.coeffs().data(), b.t.data(), b.q.coeffs().data());
    }
    for (const auto& o : g.observations) {
      auto kf = poses.find(o.keyframe);
      auto pl = planes.find(o.plane);
      if (kf == poses.end() || pl == planes.end()) continue;
      problem.AddResidualBlock(
          sgraph::KeyframePlaneCost::Create(o.local, sgraph::TangentBasis(o.local.normal),
                                            SqrtInformation<3>(o.information)),
          new ceres::HuberLoss(sc.plane_huber), kf->second.t.data(), kf->second.q.coeffs().data(),
          pl->second.n.data(), &pl->second.d);
      pl->second.observed = true;
    }
    for (const auto& r : g.rooms) {
      Eigen::Vector2d& c = centres.at(r.id);
      const Eigen::Vector2d across = CorridorAcross(g, r);
      for (int plane_id : r.planes) {
        auto pl = planes.find(plane_id);
        if (pl == planes.end() || !pl->second.observed) continue;
        // The snapshot is the S-Graph's own solution: its offsets are the measurements.
        const double distance = pl->second.n.dot(r.center) - pl->second.d;
        ceres::CostFunction* cost =
            r.type == sgraph::RoomType::kCorridor
                ? sgraph::CorridorPlaneCost::Create(distance, r.center.z(),
                                                    Eigen::Vector2d(-across.y(), across.x()),
                                                    r.center.head<2>(), sc.room_sigma,
                                                    sc.corridor_along_sigma)
                : sgraph::RoomPlaneCost::Create(distance, r.center.z(), sc.room_sigma);
        problem.AddResidualBlock(cost, new ceres::CauchyLoss(sc.room_cauchy), c.data(),
                                 pl->second.n.data(), &pl->second.d);
      }
    }
    if (!g.floors.empty()) {
      const auto& f = g.floors.front();
      floor_centre = f.center.head<2>();
      for (int room_id : f.rooms) {
        auto c = centres.find(room_id);
        if (c == centres.end() || !problem.HasParameterBlock(c->second.data())) continue;
        problem.AddResidualBlock(
            sgraph::FloorRoomCost::Create(c->second - floor_centre, sc.floor_sigma), nullptr,
            floor_centre.data(), c->second.data());
      }
    }
    auto* sphere = new ceres::SphereManifold<3>;
    for (auto& [id, p] : planes)
      if (p.observed) problem.SetManifold(p.n.data(), sphere);
  }
};

Eigen::Vector2d Rotate2(double yaw, const Eigen::Vector2d& v) {
  return Eigen::Rotation2Dd(yaw) * v;
}

}  // namespace

Eigen::Isometry3d MergeSolution::BimTMap() const {
  return geometry::IsometryFromXYYaw(bim_x_map.x(), bim_x_map.y(), bim_x_map.z(), z);
}

Eigen::Vector2d CorridorAcross(const sgraph::SGraph& s_graph, const sgraph::Room& room) {
  for (int id : room.planes) {
    for (const auto& p : s_graph.planes) {
      if (p.id != id) continue;
      const Eigen::Vector2d n = p.plane.normal.head<2>();
      if (n.norm() > 0.5) return n.normalized();
    }
  }
  return Eigen::Vector2d::Zero();
}

MergeSolution SolveMerge(const agraph::AGraph& a_graph, const sgraph::SGraph& s_graph,
                         const MatchPairs& pairs, const Eigen::Vector3d& initial,
                         const Eigen::Vector3d& prior, double z, const MergerConfig& config) {
  MergeSolution out;
  out.z = z;
  ceres::Problem problem;  // owns costs, losses and manifolds
  agraph::AGraphProblem a_problem(a_graph, config.agraph);
  a_problem.AddTo(problem);
  SGraphBlocks s;
  s.Build(s_graph, config, problem);

  Eigen::Vector3d xi = initial;
  problem.AddParameterBlock(xi.data(), 3);
  problem.AddResidualBlock(
      TransformPriorCost::Create(prior, config.prior_translation_sigma,
                                 config.prior_yaw_sigma_deg * kDegToRad),
      nullptr, xi.data());

  const double angle_sigma = config.surface_angle_sigma_deg * kDegToRad;
  const Eigen::Matrix3d surface_sqrt_info =
      Eigen::Vector3d(1.0 / angle_sigma, 1.0 / angle_sigma, 1.0 / config.surface_offset_sigma)
          .asDiagonal();
  std::set<double*> held;  // S blocks entering only through the match: held as published
  auto hold = [&](double* block, int size) {
    if (!problem.HasParameterBlock(block)) {
      problem.AddParameterBlock(block, size);
      held.insert(block);
    }
  };
  const int num_surfaces = static_cast<int>(a_graph.surfaces.size());
  const int num_rooms = static_cast<int>(a_graph.rooms.size());
  std::vector<std::pair<int, int>> surface_pairs, room_pairs;
  for (const auto& [s_id, a_id] : pairs.surfaces) {
    auto pl = s.planes.find(s_id);
    if (pl == s.planes.end() || a_id < 0 || a_id >= num_surfaces) continue;
    surface_pairs.emplace_back(s_id, a_id);
    const Eigen::Vector3d& n_a = a_graph.surfaces[a_id].plane.normal;
    // Opposed normals would zero the tangent residual: such a pair cannot enter the problem.
    if ((geometry::RotationZ(initial.z()) * pl->second.n).dot(n_a) <= 0.0) continue;
    hold(pl->second.n.data(), 3);
    hold(&pl->second.d, 1);
    problem.AddResidualBlock(SurfaceMatchCost::Create(n_a, z, surface_sqrt_info),
                             new ceres::HuberLoss(config.match_huber), xi.data(),
                             pl->second.n.data(), &pl->second.d, a_problem.SurfaceNormal(a_id),
                             a_problem.SurfaceOffset(a_id));
  }
  for (const auto& [s_id, a_id] : pairs.rooms) {
    auto c = s.centres.find(s_id);
    if (c == s.centres.end() || a_id < 0 || a_id >= num_rooms) continue;
    room_pairs.emplace_back(s_id, a_id);
    hold(c->second.data(), 2);
    const auto& room = *std::find_if(s_graph.rooms.begin(), s_graph.rooms.end(),
                                     [&](const sgraph::Room& r) { return r.id == s_id; });
    const Eigen::Vector2d across = CorridorAcross(s_graph, room);
    ceres::CostFunction* cost =
        room.type == sgraph::RoomType::kCorridor && across.norm() > 0.5
            ? CorridorMatchCost::Create(across, config.room_sigma)
            : RoomMatchCost::Create(config.room_sigma);
    problem.AddResidualBlock(cost, new ceres::HuberLoss(config.match_huber), xi.data(),
                             c->second.data(), a_problem.RoomCentre(a_id));
  }
  for (double* block : held) problem.SetParameterBlockConstant(block);

  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  options.max_num_iterations = config.max_iterations;
  options.max_solver_time_in_seconds = config.max_solver_time;
  options.num_threads = config.num_threads;
  options.logging_type = ceres::SILENT;
  options.function_tolerance = 1e-10;
  options.gradient_tolerance = 1e-12;
  options.parameter_tolerance = 1e-10;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  out.usable = summary.IsSolutionUsable();
  out.iterations = static_cast<int>(summary.iterations.size());
  out.residual_blocks = summary.num_residual_blocks;
  out.seconds = summary.total_time_in_seconds;
  out.initial_cost = summary.initial_cost;
  out.final_cost = summary.final_cost;
  out.message = summary.message;
  if (!out.usable) return out;
  xi.z() = geometry::NormalizeAngle(xi.z());
  out.bim_x_map = xi;

  ceres::Covariance::Options covariance_options;
  covariance_options.algorithm_type = ceres::SPARSE_QR;
  covariance_options.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  covariance_options.num_threads = config.num_threads;
  ceres::Covariance covariance(covariance_options);
  const std::vector<std::pair<const double*, const double*>> blocks = {{xi.data(), xi.data()}};
  if (covariance.Compute(blocks, &problem)) {
    Eigen::Matrix<double, 3, 3, Eigen::RowMajor> c;
    out.covariance_ok = covariance.GetCovarianceBlock(xi.data(), xi.data(), c.data());
    if (out.covariance_ok) out.covariance = c;
  }

  for (const auto& k : s_graph.keyframes) {
    auto b = s.poses.find(k.id);
    Eigen::Isometry3d pose = k.pose;
    if (b != s.poses.end()) {
      pose.linear() = b->second.q.normalized().toRotationMatrix();
      pose.translation() = b->second.t;
    }
    out.keyframes[k.id] = pose;
  }
  const Eigen::Isometry3d bim_T_map = out.BimTMap();
  for (const auto& [s_id, a_id] : surface_pairs) {
    // Against the S-Graph as published (its evidence), not as the merge may have bent it.
    const auto& p = *std::find_if(s_graph.planes.begin(), s_graph.planes.end(),
                                  [&](const sgraph::Plane& x) { return x.id == s_id; });
    const geometry::Plane moved = p.plane.Transformed(bim_T_map);
    const geometry::Plane a(Eigen::Map<const Eigen::Vector3d>(a_problem.SurfaceNormal(a_id)),
                            *a_problem.SurfaceOffset(a_id));
    PairResidual r;
    r.s_id = s_id;
    r.a_id = a_id;
    const double cosine = std::clamp(moved.normal.dot(a.normal), -1.0, 1.0);
    r.used = cosine > 0.0;
    r.angle_deg = std::acos(cosine) / kDegToRad;
    r.offset = std::abs(moved.d - a.d);
    r.chi2 = std::pow(r.angle_deg * kDegToRad / angle_sigma, 2) +
             std::pow(r.offset / config.surface_offset_sigma, 2);
    r.dof = 3;
    out.surfaces.push_back(r);
  }
  for (const auto& [s_id, a_id] : room_pairs) {
    const auto& room = *std::find_if(s_graph.rooms.begin(), s_graph.rooms.end(),
                                     [&](const sgraph::Room& x) { return x.id == s_id; });
    const Eigen::Vector2d across = CorridorAcross(s_graph, room);
    const Eigen::Vector2d e = Rotate2(xi.z(), room.center.head<2>()) + xi.head<2>() -
                              Eigen::Map<const Eigen::Vector2d>(a_problem.RoomCentre(a_id));
    PairResidual r;
    r.s_id = s_id;
    r.a_id = a_id;
    r.corridor = room.type == sgraph::RoomType::kCorridor && across.norm() > 0.5;
    r.distance = r.corridor ? std::abs(Rotate2(xi.z(), across).dot(e)) : e.norm();
    r.chi2 = std::pow(r.distance / config.room_sigma, 2);
    r.dof = r.corridor ? 1 : 2;
    out.rooms.push_back(r);
  }
  return out;
}

}  // namespace merging
}  // namespace is_graphs
