#include "is_graphs/agraph/agraph_problem.h"

#include <ceres/loss_function.h>
#include <ceres/solver.h>

#include <cmath>
#include <memory>
#include <sstream>

#include "is_graphs/agraph/cost/doorway_cost.h"
#include "is_graphs/agraph/cost/plane_prior_cost.h"
#include "is_graphs/agraph/cost/point_prior_cost.h"
#include "is_graphs/agraph/cost/wall_centre_cost.h"
#include "is_graphs/common/ceres_compat.h"
#include "is_graphs/common/disjoint_sets.h"

namespace is_graphs {
namespace agraph {
namespace {

std::string CheckPositive(const char* name, double value) {
  if (std::isfinite(value) && value > 0.0) return "";
  std::ostringstream out;
  out << name << " must be a positive number, got " << value;
  return out.str();
}

Eigen::Matrix3d SqrtInformation(double sigma_xy, double sigma_z) {
  return Eigen::Vector3d(1.0 / sigma_xy, 1.0 / sigma_xy, 1.0 / sigma_z).asDiagonal();
}

}  // namespace

std::string AGraphProblemConfig::Validate() const {
  for (const auto& [name, value] :
       {std::pair<const char*, double>{"plane_angle_sigma", plane_angle_sigma},
        {"plane_offset_sigma", plane_offset_sigma},
        {"wall_centre_sigma", wall_centre_sigma},
        {"doorway_sigma", doorway_sigma},
        {"room_centre_sigma", room_centre_sigma}}) {
    const std::string error = CheckPositive(name, value);
    if (!error.empty()) return error;
  }
  if (!std::isfinite(huber_scale) || huber_scale < 0.0) {
    return "huber_scale must be >= 0 (0 disables the robust loss), got " +
           std::to_string(huber_scale);
  }
  if (max_iterations < 1) {
    return "max_iterations must be >= 1, got " + std::to_string(max_iterations);
  }
  if (num_threads < 1) return "num_threads must be >= 1, got " + std::to_string(num_threads);
  return "";
}

std::string AGraphSolveSummary::ToString() const {
  std::ostringstream out;
  out << "solve: " << (usable ? "usable" : "NOT usable") << ", cost " << initial_cost << " -> "
      << final_cost << ", " << iterations << " iterations, " << time_s << " s, " << parameter_blocks
      << " parameter blocks, " << residual_blocks << " residual blocks (" << termination << ")";
  return out.str();
}

AGraphProblem::AGraphProblem(const AGraph& graph, const AGraphProblemConfig& config)
    : measured_(graph), config_(config) {
  for (const WallSurface& s : graph.surfaces) {
    normals_.push_back(s.plane.normal.normalized());
    offsets_.push_back(s.plane.d);
  }
  for (const Wall& w : graph.walls) wall_centres_.push_back(w.center);
  for (const Room& r : graph.rooms) room_centres_.push_back(r.center);
  for (const Doorway& d : graph.doorways) doorway_positions_.push_back(d.position);
}

void AGraphProblem::AddTo(ceres::Problem& problem) {
  AddParts(problem, std::vector<bool>(normals_.size(), true),
           std::vector<bool>(room_centres_.size(), true));
}

void AGraphProblem::AddConnectedTo(ceres::Problem& problem, const std::vector<int>& surfaces,
                                   const std::vector<int>& rooms) {
  // The factor graph's components: a wall joins its two faces, a doorway its rooms. Every other
  // element has only its prior (a component of its own).
  const int num_surfaces = static_cast<int>(normals_.size());
  const int num_rooms = static_cast<int>(room_centres_.size());
  DisjointSets pieces(num_surfaces + num_rooms);  // surfaces, then rooms
  for (const Wall& w : measured_.walls) pieces.Join(w.surface_a, w.surface_b);
  for (const Doorway& d : measured_.doorways)
    for (size_t i = 1; i < d.rooms.size(); ++i)
      pieces.Join(num_surfaces + d.rooms[0], num_surfaces + d.rooms[i]);
  std::vector<bool> seed(num_surfaces + num_rooms, false);
  for (int s : surfaces)
    if (s >= 0 && s < num_surfaces) seed[pieces.Find(s)] = true;
  for (int r : rooms)
    if (r >= 0 && r < num_rooms) seed[pieces.Find(num_surfaces + r)] = true;
  std::vector<bool> keep_surface(num_surfaces), keep_room(num_rooms);
  for (int i = 0; i < num_surfaces; ++i) keep_surface[i] = seed[pieces.Find(i)];
  for (int i = 0; i < num_rooms; ++i) keep_room[i] = seed[pieces.Find(num_surfaces + i)];
  AddParts(problem, keep_surface, keep_room);
}

void AGraphProblem::AddParts(ceres::Problem& problem, const std::vector<bool>& surfaces,
                             const std::vector<bool>& rooms) {
  std::unique_ptr<ceres::LossFunction> loss_owner(
      config_.huber_scale > 0.0 ? new ceres::HuberLoss(config_.huber_scale) : nullptr);
  ceres::LossFunction* loss = loss_owner.get();
  bool loss_used = false;
  std::unique_ptr<ceres_compat::Parameterization> sphere_owner(ceres_compat::NewUnitSphere3());
  bool sphere_used = false;
  for (size_t i = 0; i < normals_.size(); ++i) {
    if (!surfaces[i]) continue;
    problem.AddParameterBlock(normals_[i].data(), 3, sphere_owner.get());
    problem.AddParameterBlock(&offsets_[i], 1);
    sphere_used = true;
  }

  const Eigen::Matrix3d plane_info =
      SqrtInformation(config_.plane_angle_sigma, config_.plane_offset_sigma);
  for (const WallSurface& s : measured_.surfaces) {
    if (!surfaces[s.id]) continue;
    problem.AddResidualBlock(PlanePriorCost::Create(s.plane, plane_info), loss,
                             normals_[s.id].data(), &offsets_[s.id]);
    loss_used = true;
  }

  const Eigen::Matrix3d wall_info = Eigen::Matrix3d::Identity() / config_.wall_centre_sigma;
  for (const Wall& w : measured_.walls) {
    if (!surfaces[w.surface_a]) continue;  // then not its other face either (AddConnectedTo)
    problem.AddResidualBlock(WallCentreCost::Create(w.start, wall_info), loss,
                             wall_centres_[w.id].data(), normals_[w.surface_a].data(),
                             &offsets_[w.surface_a], normals_[w.surface_b].data(),
                             &offsets_[w.surface_b]);
    loss_used = true;
  }

  const Eigen::Matrix3d room_info = Eigen::Matrix3d::Identity() / config_.room_centre_sigma;
  for (const Room& r : measured_.rooms) {
    if (!rooms[r.id]) continue;
    problem.AddResidualBlock(PointPriorCost::Create(r.center, room_info), loss,
                             room_centres_[r.id].data());
    loss_used = true;
  }

  const Eigen::Matrix3d doorway_info = Eigen::Matrix3d::Identity() / config_.doorway_sigma;
  for (const Doorway& d : measured_.doorways) {
    for (int room : d.rooms) {
      if (!rooms[room]) continue;
      const Eigen::Vector3d offset = measured_.rooms[room].center - d.position;
      problem.AddResidualBlock(DoorwayRoomCost::Create(offset, doorway_info), loss,
                               doorway_positions_[d.id].data(), room_centres_[room].data());
      loss_used = true;
    }
  }
  // The problem owns (the default ceres::Problem::Options) what it was handed.
  if (loss_used) loss_owner.release();
  if (sphere_used) sphere_owner.release();
}

AGraphSolveSummary AGraphProblem::Solve() {
  ceres::Problem problem;
  AddTo(problem);
  AGraphSolveSummary result;
  result.residual_blocks = problem.NumResidualBlocks();
  result.parameter_blocks = problem.NumParameterBlocks();
  if (problem.NumResidualBlocks() == 0) {
    result.usable = true;
    result.termination = "empty problem";
    return result;
  }

  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.sparse_linear_algebra_library_type =
      ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::SUITE_SPARSE) ? ceres::SUITE_SPARSE
                                                                            : ceres::EIGEN_SPARSE;
  options.max_num_iterations = config_.max_iterations;
  options.num_threads = config_.num_threads;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;

  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  result.usable = summary.IsSolutionUsable();
  result.initial_cost = summary.initial_cost;
  result.final_cost = summary.final_cost;
  result.iterations = summary.num_successful_steps + summary.num_unsuccessful_steps;
  result.time_s = summary.total_time_in_seconds;
  result.termination = summary.message;
  return result;
}

bool AGraphProblem::WriteBack(AGraph& graph) const {
  if (graph.surfaces.size() != normals_.size() || graph.walls.size() != wall_centres_.size() ||
      graph.rooms.size() != room_centres_.size() ||
      graph.doorways.size() != doorway_positions_.size()) {
    return false;
  }
  for (size_t i = 0; i < normals_.size(); ++i) {
    graph.surfaces[i].plane = geometry::Plane(normals_[i], offsets_[i]);
  }
  for (size_t i = 0; i < wall_centres_.size(); ++i) graph.walls[i].center = wall_centres_[i];
  for (size_t i = 0; i < room_centres_.size(); ++i) graph.rooms[i].center = room_centres_[i];
  for (size_t i = 0; i < doorway_positions_.size(); ++i) {
    graph.doorways[i].position = doorway_positions_[i];
  }
  return true;
}

}  // namespace agraph
}  // namespace is_graphs
