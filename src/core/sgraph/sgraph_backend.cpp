#include "is_graphs/sgraph/sgraph_backend.h"

#include <ceres/problem.h>
#include <ceres/solver.h>

#include "is_graphs/sgraph/sgraph_factors.h"

namespace is_graphs {
namespace sgraph {

BackendSummary OptimizeSGraph(BackendProblem& problem, const BackendConfig& config) {
  BackendSummary summary;
  summary.num_keyframes = static_cast<int>(problem.keyframes.size());
  summary.num_variable_keyframes = 0;
  for (const auto& k : problem.keyframes)
    summary.num_variable_keyframes += problem.constant_keyframes.count(k.id) ? 0 : 1;
  if (problem.keyframes.empty()) {
    summary.message = "no keyframes";
    return summary;
  }
  ceres::Problem ceres_problem;  // owns costs, losses and manifolds
  SGraphFactors factors(problem);
  factors.AddTo(problem, config, ceres_problem);

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

  factors.WriteBack(problem);
  return summary;
}

}  // namespace sgraph
}  // namespace is_graphs
