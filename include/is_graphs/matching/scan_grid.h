#pragma once

// The pieces of ScanSearch (scan_search.h): the score grid of one storey with its max-pooled
// pyramid, and the points of one search prepared on it (thinned, centred, rotated per yaw
// interval), which gives every branch-and-bound node its upper bound. Public for the tests.
#include <Eigen/Core>
#include <limits>
#include <utility>
#include <vector>

#include "is_graphs/matching/rigid_fit.h"

namespace is_graphs {
namespace matching {

/// exp(-d² / 2σ²) of the distance d to the nearest segment, per cell of `resolution`. World cell
/// (i, j) is [i r, (i+1) r) x [j r, (j+1) r), its value taken at its centre; 0 farther than 6σ
/// from every segment and outside the grid. Level h of the pyramid holds, at cell (i, j), the
/// max over the 2^h x 2^h cells from (i, j) up (Cartographer's precomputation grids).
class ScanGrid {
 public:
  ScanGrid(const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& segments,
           double resolution, double sigma, int levels);

  int levels() const { return static_cast<int>(pyramid_.size()); }
  double resolution() const { return resolution_; }
  /// The world cells of the walls' extent (min and max corner, inclusive).
  Eigen::Vector2i walls_min() const { return walls_min_; }
  Eigen::Vector2i walls_max() const { return walls_max_; }
  /// The value of world cell (i, j) at pyramid level h (0: the score grid itself).
  float At(int h, int i, int j) const {
    const int a = i - origin_.x(), b = j - origin_.y();
    if (static_cast<unsigned>(a) >= static_cast<unsigned>(size_.x()) ||
        static_cast<unsigned>(b) >= static_cast<unsigned>(size_.y()))
      return 0.0f;
    return pyramid_[h][static_cast<size_t>(b) * size_.x() + a];
  }
  /// The world cell holding world point p.
  Eigen::Vector2i CellOf(const Eigen::Vector2d& p) const;

  // The raw layout, for the tight loop of ScanProblem: cell (i, j) at index
  // (j - origin.y) * size.x + (i - origin.x) of level h.
  const float* level(int h) const { return pyramid_[h].data(); }
  Eigen::Vector2i origin() const { return origin_; }
  Eigen::Vector2i size() const { return size_; }

 private:
  double resolution_;
  Eigen::Vector2i origin_, size_, walls_min_, walls_max_;
  std::vector<std::vector<float>> pyramid_;
};

/// The points of one search on one grid. Yaw step k is the angle k * yaw_step, k in
/// [0, yaw_steps); translation cell (x, y) puts the points' centroid at (x r, y r) in B. A node of
/// level l covers translation cells [x, x + 2^l) x [y, y + 2^l) and yaw steps
/// [yaw, yaw + 2^yaw_level(l)); its bound is the mean over the points of the pyramid at the cell
/// each point reaches first, at the level whose window holds every cell the point visits in the
/// node: a true upper bound of every leaf under it. Level 0 (yaw_level 0) is a leaf: its exact
/// score.
class ScanProblem {
 public:
  struct Node {
    int x{0}, y{0}, yaw{0}, level{0};
  };

  /// `points` (in M, at least one) thinned to one per cell of the grid's resolution (their mean);
  /// yaw step `yaw_step` (rad, 0: from the resolution and the points' reach).
  ScanProblem(const ScanGrid& grid, const std::vector<Eigen::Vector2d>& points, double yaw_step);

  /// The node's upper bound; once the points so far show it below `threshold`, a looser upper
  /// bound still below it (the rest counted at 1) without scoring the rest.
  double Bound(const Node& node, double threshold = -std::numeric_limits<double>::infinity()) const;
  /// B_x_M of leaf (x, y, yaw).
  Pose2 LeafPose(int x, int y, int yaw) const;
  int yaw_steps() const { return yaw_steps_; }
  double yaw_step() const { return yaw_step_; }
  int yaw_level(int level) const { return yaw_level_[level]; }
  int max_level() const { return static_cast<int>(yaw_level_.size()) - 1; }
  const std::vector<Eigen::Vector2d>& points() const { return points_; }
  const Eigen::Vector2d& centroid() const { return centroid_; }

  /// Thinned to one point per cell of `resolution` (the mean of the cell's points), interleaved
  /// (cell order taken with a stride of about 0.618 n) so that the first points of a bound spread
  /// over the whole slice and a hopeless node shows it early.
  static std::vector<Eigen::Vector2d> Thin(const std::vector<Eigen::Vector2d>& points,
                                           double resolution);

 private:
  const ScanGrid& grid_;
  std::vector<Eigen::Vector2d> points_;  // thinned
  Eigen::Vector2d centroid_{Eigen::Vector2d::Zero()};
  double yaw_step_{0.0};
  int yaw_steps_{1};
  std::vector<int> yaw_level_;   // per node level
  std::vector<int> pool_level_;  // per node level: the pyramid level of its bound
  // Per yaw level g and interval j (yaw steps [j 2^g, (j+1) 2^g)): the first cell each point
  // visits, relative to the translation cell, as x and y; and their min and max over the points.
  struct Rotated {
    std::vector<int> x, y;
    Eigen::Vector2i min, max;
  };
  std::vector<std::vector<Rotated>> rotated_;
};

}  // namespace matching
}  // namespace is_graphs
