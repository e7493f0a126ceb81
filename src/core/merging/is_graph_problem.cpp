#include "is_graphs/merging/is_graph_problem.h"

#include <ceres/covariance.h>
#include <ceres/loss_function.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <utility>
#include <vector>

#include "is_graphs/agraph/agraph_problem.h"
#include "is_graphs/geometry/se3.h"
#include "is_graphs/merging/cost/corridor_match_cost.h"
#include "is_graphs/merging/cost/deviated_room_match_cost.h"
#include "is_graphs/merging/cost/deviated_surface_match_cost.h"
#include "is_graphs/merging/cost/room_match_cost.h"
#include "is_graphs/merging/cost/surface_match_cost.h"
#include "is_graphs/merging/cost/transform_prior_cost.h"
#include "is_graphs/merging/room_centre_shift.h"
#include "is_graphs/sgraph/backend_window.h"
#include "is_graphs/sgraph/sgraph_factors.h"
#include "wall_deviation_blocks.h"

namespace is_graphs {
namespace merging {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

Eigen::Vector2d Rotate2(double yaw, const Eigen::Vector2d& v) {
  return Eigen::Rotation2Dd(yaw) * v;
}

// σ of a room-centre match: the merge's own room_sigma, or looser where the S-Graph says its
// centre is (a polygonal room: the centroid of the part seen). The largest σ of the x-y block;
// an information that is not positive definite (not set) leaves room_sigma.
double RoomCentreSigma(const sgraph::Room& room, const MergerConfig& config) {
  const Eigen::Matrix2d info = room.information.topLeftCorner<2, 2>();
  if (!info.allFinite()) return config.room_sigma;
  const double smallest = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(info).eigenvalues()(0);
  if (!(smallest > 0.0)) return config.room_sigma;
  return std::max(config.room_sigma, 1.0 / std::sqrt(smallest));
}

/// The S-Graph as the merge sees it: the newest `window_keyframes` keyframes move with B_x_M, and
/// with them the planes they observe and the rooms on those; older keyframes enter held as the
/// S-Graph published them where they tie something that moves, the rest stays out
/// (sgraph::SelectWindow). The merge's cost stays bounded on long runs; what it moves is what the
/// pose uses. Planes and rooms left out still enter through a match, held as published.
sgraph::BackendProblem WindowedSGraph(const sgraph::SGraph& graph, const MergerConfig& config) {
  sgraph::BackendProblem s = sgraph::BackendProblemFromSnapshot(graph);
  if (!config.optimize_sgraph) return s;
  sgraph::BackendConfig window = config.sgraph;
  window.window_keyframes = config.window_keyframes;
  const std::vector<sgraph::Keyframe> keyframes = std::move(s.keyframes);
  const std::vector<sgraph::PlaneObservation> observations = std::move(s.observations);
  sgraph::SelectWindow(keyframes, observations, window, s);
  return s;
}

}  // namespace

Eigen::Isometry3d MergeSolution::BimTMap() const {
  return geometry::IsometryFromXYYaw(bim_x_map.x(), bim_x_map.y(), bim_x_map.z(), z);
}

std::map<int, double> TurnedWalls(const std::map<int, std::vector<double>>& turns, double release) {
  std::vector<std::pair<int, double>> mean;
  for (const auto& [wall, t] : turns) {
    if (t.empty()) continue;
    double sum = 0.0;
    for (double a : t) sum += a;
    mean.emplace_back(wall, sum / static_cast<double>(t.size()));
  }
  if (mean.size() < 3) return {};  // no median to tell a turned wall from a turned pose
  std::vector<double> sorted;
  for (const auto& m : mean) sorted.push_back(m.second);
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double median = sorted[sorted.size() / 2];
  std::map<int, double> out;
  for (const auto& [wall, a] : mean)
    if (std::abs(a - median) > release) out[wall] = a - median;
  return out;
}

std::map<int, Eigen::Vector2d> ReleasedTurns(const std::map<int, double>& turned,
                                             std::map<int, Eigen::Vector2d> starts) {
  for (const auto& [wall, turn] : turned) {
    Eigen::Vector2d& start = starts.try_emplace(wall, Eigen::Vector2d::Zero()).first->second;
    if (!(std::abs(start.y() - turn) < 0.5 * std::abs(turn))) start.y() = turn;
  }
  return starts;
}

MergeSolution SolveMerge(const agraph::AGraph& a_graph, const sgraph::SGraph& s_graph,
                         const MatchPairs& pairs, const Eigen::Vector3d& initial,
                         const Eigen::Vector3d& prior, double z, const MergerConfig& config,
                         const std::map<int, Eigen::Vector2d>& initial_deviations) {
  MergeSolution out;
  out.z = z;
  ceres::Problem problem;  // owns costs, losses and manifolds
  agraph::AGraphProblem a_problem(a_graph, config.agraph);
  {
    // Only the parts of the A-Graph the matches touch: the rest shares no factor with them (on
    // a building of several storeys, most of it; issue 22's hour-long merge latency).
    std::vector<int> matched_surfaces, matched_rooms;
    for (const auto& [s_id, a_ids] : pairs.surfaces)
      matched_surfaces.insert(matched_surfaces.end(), a_ids.begin(), a_ids.end());
    for (const auto& [s_id, a_id] : pairs.rooms) matched_rooms.push_back(a_id);
    a_problem.AddConnectedTo(problem, matched_surfaces, matched_rooms);
  }
  const sgraph::BackendProblem s_problem = WindowedSGraph(s_graph, config);
  sgraph::SGraphFactors s(s_problem);
  if (config.optimize_sgraph) {
    s.AddTo(s_problem, config.sgraph, problem);
    // The odometry's scale as the S-Graph estimated it over the whole run (the window sees less).
    if (problem.HasParameterBlock(&s.odometry_scale))
      problem.SetParameterBlockConstant(&s.odometry_scale);
  }

  Eigen::Vector3d xi = initial;
  problem.AddParameterBlock(xi.data(), 3);
  problem.AddResidualBlock(TransformPriorCost::Create(prior, config.prior_translation_sigma,
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
  std::map<int, Eigen::Vector2d> starts = initial_deviations;
  std::set<int> free_turns;  // walls seen turned: their turns have no prior
  // Reads `starts` and `free_turns` as blocks are made.
  WallDeviationBlocks deviations(a_graph, config, starts, free_turns);
  if (config.estimate_wall_deviations) {
    std::map<int, std::vector<double>> turns;  // per wall, the turns its S-planes show
    for (const auto& [s_id, a_ids] : pairs.surfaces) {
      const auto pl = s.planes.find(s_id);
      if (pl == s.planes.end()) continue;
      const Eigen::Vector3d n_b = geometry::RotationZ(initial.z()) * pl->second.n;
      for (int a_id : a_ids) {
        if (a_id < 0 || a_id >= static_cast<int>(a_graph.surfaces.size())) continue;
        const Eigen::Vector3d& n_a = a_graph.surfaces[a_id].plane.normal;
        const int wall = deviations.WallOf(a_id);
        if (wall < 0 || n_b.head<2>().dot(n_a.head<2>()) <= 0.0) continue;
        turns[wall].push_back(
            std::atan2(n_a.x() * n_b.y() - n_a.y() * n_b.x(), n_a.head<2>().dot(n_b.head<2>())));
      }
    }
    const std::map<int, double> turned =
        TurnedWalls(turns, config.wall_turn_release_deg * kDegToRad);
    for (const auto& t : turned) free_turns.insert(t.first);
    starts = ReleasedTurns(turned, std::move(starts));
  }
  const int num_surfaces = static_cast<int>(a_graph.surfaces.size());
  const int num_rooms = static_cast<int>(a_graph.rooms.size());
  std::vector<std::pair<int, int>> surface_pairs, room_pairs;
  for (const auto& [s_id, a_ids] : pairs.surfaces) {
    auto pl = s.planes.find(s_id);
    if (pl == s.planes.end()) continue;
    // An S-plane along k collinear A-surfaces: each pair weighs 1/k (the plane counts once).
    const double share = 1.0 / static_cast<double>(std::max<size_t>(1, a_ids.size()));
    for (int a_id : a_ids) {
      if (a_id < 0 || a_id >= num_surfaces) continue;
      surface_pairs.emplace_back(s_id, a_id);
      const Eigen::Vector3d& n_a = a_graph.surfaces[a_id].plane.normal;
      // Opposed normals would zero the tangent residual: such a pair cannot enter the problem.
      if ((geometry::RotationZ(initial.z()) * pl->second.n).dot(n_a) <= 0.0) continue;
      hold(pl->second.n.data(), 3);
      hold(&pl->second.d, 1);
      ceres::LossFunction* loss = new ceres::HuberLoss(config.match_huber);
      if (share < 1.0) loss = new ceres::ScaledLoss(loss, share, ceres::TAKE_OWNERSHIP);
      const int wall = deviations.WallOf(a_id);
      if (wall < 0) {
        problem.AddResidualBlock(SurfaceMatchCost::Create(n_a, z, surface_sqrt_info), loss,
                                 xi.data(), pl->second.n.data(), &pl->second.d,
                                 a_problem.SurfaceNormal(a_id), a_problem.SurfaceOffset(a_id));
        continue;
      }
      problem.AddResidualBlock(
          DeviatedSurfaceMatchCost::Create(n_a, a_graph.walls[wall].center.head<2>(),
                                           deviations.Normal(wall), z, surface_sqrt_info),
          loss, xi.data(), pl->second.n.data(), &pl->second.d, a_problem.SurfaceNormal(a_id),
          a_problem.SurfaceOffset(a_id), deviations.Block(wall, problem));
    }
  }
  for (const auto& [s_id, a_id] : pairs.rooms) {
    auto c = s.centres.find(s_id);
    if (c == s.centres.end() || a_id < 0 || a_id >= num_rooms) continue;
    room_pairs.emplace_back(s_id, a_id);
    hold(c->second.data(), 2);
    const auto& room = *std::find_if(s_graph.rooms.begin(), s_graph.rooms.end(),
                                     [&](const sgraph::Room& r) { return r.id == s_id; });
    const Eigen::Vector2d across = sgraph::CorridorAcross(s_graph, room);
    const double sigma = RoomCentreSigma(room, config);
    const bool corridor = room.type == sgraph::RoomType::kCorridor && across.norm() > 0.5;
    // The A-room's centre moves with the offsets of its walls (those with a state).
    std::vector<Eigen::Vector2d> per_offset;
    std::vector<double*> blocks = {xi.data(), c->second.data(), a_problem.RoomCentre(a_id)};
    if (config.estimate_wall_deviations) {
      for (const RoomCentreShift& shift : RoomCentreShifts(a_graph, a_graph.rooms[a_id])) {
        auto block = deviations.blocks().find(shift.wall);
        if (block == deviations.blocks().end()) continue;
        per_offset.push_back(shift.per_offset);
        blocks.push_back(block->second.data());
      }
    }
    ceres::CostFunction* cost =
        !per_offset.empty()
            ? DeviatedRoomMatchCost::Create(std::move(per_offset),
                                            corridor ? across : Eigen::Vector2d::Zero(), sigma)
        : corridor ? CorridorMatchCost::Create(across, sigma)
                   : RoomMatchCost::Create(sigma);
    problem.AddResidualBlock(cost, new ceres::HuberLoss(config.match_huber), blocks);
  }
  for (double* block : held) problem.SetParameterBlockConstant(block);

  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  options.max_num_iterations = config.max_iterations;
  options.max_solver_time_in_seconds = config.max_solver_time;
  options.num_threads = config.num_threads;
  options.logging_type = ceres::SILENT;
  options.function_tolerance = config.function_tolerance;
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
  std::vector<std::pair<const double*, const double*>> blocks = {{xi.data(), xi.data()}};
  for (auto& [wall, block] : deviations.blocks()) blocks.emplace_back(block.data(), block.data());
  const bool covariance_computed = covariance.Compute(blocks, &problem);
  if (covariance_computed) {
    Eigen::Matrix<double, 3, 3, Eigen::RowMajor> c;
    out.covariance_ok = covariance.GetCovarianceBlock(xi.data(), xi.data(), c.data());
    if (out.covariance_ok) out.covariance = c;
  }
  for (auto& [wall, block] : deviations.blocks()) {
    WallDeviationEstimate w;
    w.wall_id = wall;
    w.offset = block.x();
    w.angle = block.y();
    w.pairs = deviations.Pairs(wall);
    Eigen::Matrix<double, 2, 2, Eigen::RowMajor> c;
    if (covariance_computed &&
        covariance.GetCovarianceBlock(block.data(), block.data(), c.data())) {
      w.offset_sigma = std::sqrt(std::max(0.0, c(0, 0)));
      w.angle_sigma = std::sqrt(std::max(0.0, c(1, 1)));
    }
    out.walls.push_back(w);
  }

  for (const auto& k : s_graph.keyframes) {
    auto b = s.poses.find(k.id);
    Eigen::Isometry3d pose = k.pose;
    if (config.optimize_sgraph && b != s.poses.end()) {
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
    const Eigen::Vector2d across = sgraph::CorridorAcross(s_graph, room);
    const Eigen::Vector2d e = Rotate2(xi.z(), room.center.head<2>()) + xi.head<2>() -
                              Eigen::Map<const Eigen::Vector2d>(a_problem.RoomCentre(a_id));
    PairResidual r;
    r.s_id = s_id;
    r.a_id = a_id;
    r.corridor = room.type == sgraph::RoomType::kCorridor && across.norm() > 0.5;
    r.distance = r.corridor ? std::abs(Rotate2(xi.z(), across).dot(e)) : e.norm();
    r.chi2 = std::pow(r.distance / RoomCentreSigma(room, config), 2);
    r.dof = r.corridor ? 1 : 2;
    out.rooms.push_back(r);
  }
  return out;
}

}  // namespace merging
}  // namespace is_graphs
