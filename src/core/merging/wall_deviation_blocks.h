#pragma once
// The merge's as-built wall deviation states (issue 21), one per A-wall with a matched surface:
// SolveMerge's bookkeeping, not part of the public API.

#include <ceres/loss_function.h>
#include <ceres/problem.h>

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/merging/cost/wall_deviation_prior_cost.h"
#include "is_graphs/merging/merger_config.h"

namespace is_graphs {
namespace merging {

/// The as-built deviation states of the A-walls that have a matched surface, made on demand,
/// each with its Cauchy prior at the plan; a wall in `free_turns` (seen turned) has none on its
/// turn.
class WallDeviationBlocks {
 public:
  WallDeviationBlocks(const agraph::AGraph& a_graph, const MergerConfig& config,
                      const std::map<int, Eigen::Vector2d>& initial,
                      const std::set<int>& free_turns)
      : a_graph_(a_graph),
        config_(config),
        initial_(initial),
        free_turns_(free_turns),
        wall_of_(a_graph.surfaces.size(), -1) {
    if (!config.estimate_wall_deviations) return;
    for (const agraph::Wall& w : a_graph.walls) {
      for (int surface : {w.surface_a, w.surface_b})
        if (surface >= 0 && surface < static_cast<int>(wall_of_.size())) wall_of_[surface] = w.id;
    }
  }

  /// The wall of A-surface `surface` whose deviation the match moves, or -1.
  int WallOf(int surface) const { return wall_of_[surface]; }

  /// The wall's plan normal: its surface_a's, horizontal.
  Eigen::Vector2d Normal(int wall) const {
    const Eigen::Vector2d n =
        a_graph_.surfaces[a_graph_.walls[wall].surface_a].plane.normal.head<2>();
    return n.norm() > 1e-9 ? Eigen::Vector2d(n.normalized()) : Eigen::Vector2d::UnitX();
  }
  /// The wall's deviation block (offset, angle), added to `problem` with its prior (under a
  /// Cauchy loss; on the offset alone for a wall in `free_turns`) the first time; counts the
  /// pairs resting on it.
  double* Block(int wall, ceres::Problem& problem) {
    const auto start = initial_.find(wall);
    auto [it, added] = blocks_.try_emplace(
        wall, start != initial_.end() && start->second.allFinite() ? start->second
                                                                   : Eigen::Vector2d::Zero());
    ++pairs_[wall];
    if (added) {
      problem.AddParameterBlock(it->second.data(), 2);
      constexpr double kFree = std::numeric_limits<double>::infinity();
      const bool free_turn = free_turns_.count(wall) > 0;
      problem.AddResidualBlock(
          WallDeviationPriorCost::Create(
              config_.wall_deviation_offset_sigma,
              free_turn ? kFree : config_.wall_deviation_angle_sigma_deg * M_PI / 180.0),
          new ceres::CauchyLoss(1.0), it->second.data());
    }
    return it->second.data();
  }

  std::map<int, Eigen::Vector2d>& blocks() { return blocks_; }
  int Pairs(int wall) const { return pairs_.at(wall); }

 private:
  const agraph::AGraph& a_graph_;
  const MergerConfig& config_;
  const std::map<int, Eigen::Vector2d>& initial_;
  const std::set<int>& free_turns_;
  std::vector<int> wall_of_;
  std::map<int, Eigen::Vector2d> blocks_;  // wall id -> (offset, angle); stable addresses
  std::map<int, int> pairs_;
};

}  // namespace merging
}  // namespace is_graphs
