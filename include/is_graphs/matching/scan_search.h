#pragma once

// A certified scan-to-BIM search: a multi-resolution branch-and-bound over (x, y, yaw) of one
// storey (as Cartographer's fast correlative scan matcher), scoring 2-D wall points of the
// first keyframes (a horizontal slice of their scans, in M) against a grid of the storey's
// wall-surfaces. Not only the best pose: every region whose upper bound comes within `margin`
// of the best is searched down to the finest cell, so the answer is the set of poses the
// points cannot tell apart, and the bound is its certificate: every pose outside the set
// scores less than best - margin.
#include <Eigen/Core>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/matching/rigid_fit.h"

namespace is_graphs {
namespace matching {

class ScanProblem;  // scan_grid.h

struct ScanSearchConfig {
  double resolution{0.05};  // m: the finest cell of the wall grid and of the translation
  // A point at distance d from the nearest wall face scores exp(-d² / 2 sigma²); the score of a
  // pose is the mean over the points (0..1).
  double sigma{0.10};
  // The storey's wall-surfaces in the grid: those spanning any of [band_low, band_high] above
  // the storey's elevation (the slice the points are taken from).
  double band_low{0.9};
  double band_high{2.1};
  double angular_step_deg{0.0};  // 0: from the resolution and the points' reach
  double margin{0.05};           // of the mean score: poses within it of the best are kept
  int max_set{32};               // more distinct poses within the margin: kTooMany
  int min_points{60};            // fewer points: kTooFewPoints
  double distinct_xy{0.5};       // m: poses closer than this and distinct_yaw_deg are one
  double distinct_yaw_deg{5.0};
  double window_margin{2.0};  // m beyond the storey's walls where the points' centre may lie

  /// "" when every value is in range, else what is wrong (names the key and its range).
  std::string Validate() const;
};

/// One pose of the certified set: B_x_M and its score (mean over the points, 0..1).
struct ScanPose {
  Pose2 bim_T_map;
  double score{0.0};
};

struct ScanSearchResult {
  enum class Status { kOk, kNoWalls, kTooFewPoints, kTooMany };
  Status status{Status::kOk};
  std::string reason;         // for every status but kOk: why, with its numbers
  std::vector<ScanPose> set;  // best first, one per distinct pose; empty unless kOk
  double best{0.0};           // the best pose's score
  double margin{0.0};         // the margin used
  long nodes{0};              // branch-and-bound nodes scored
  double milliseconds{0.0};
};

/// The storeys' wall grids, built once per A-Graph; Search is const and thread-compatible.
class ScanSearch {
 public:
  ScanSearch() = default;
  /// `config` must pass Validate.
  ScanSearch(const agraph::AGraph& graph, const ScanSearchConfig& config);

  /// The set of B_x_M (yaw over the full turn) under which `points` (x, y in M) lie on the
  /// wall-surfaces of `storey` (an A-Graph storey id) within the margin of the best.
  ScanSearchResult Search(const std::vector<Eigen::Vector2d>& points, int storey) const;
  /// The score of `points` under `bim_T_map` on `storey` (mean over the points, thinned as
  /// Search thins them: one per cell of `resolution`, their mean; 0 for an unknown storey or no
  /// points). At a leaf of the search it is the leaf's score.
  double Score(const std::vector<Eigen::Vector2d>& points, const Pose2& bim_T_map,
               int storey) const;
  bool HasWalls(int storey) const;
  const ScanSearchConfig& config() const { return config_; }

  // For tests and tools: the search's discretization and bounds (scan_grid.h).
  /// The points prepared on `storey`'s grid (nullptr without walls or points); lives as long
  /// as this ScanSearch.
  std::unique_ptr<ScanProblem> Problem(const std::vector<Eigen::Vector2d>& points,
                                       int storey) const;
  /// The translation cells searched on `storey` (first and last, inclusive; the walls' extent
  /// ± window_margin), false without walls.
  bool TranslationCells(int storey, Eigen::Vector2i* first, Eigen::Vector2i* last) const;

 private:
  struct Grid;  // per storey: the score grid and its max-pooled pyramid (scan_search.cpp)
  ScanSearchConfig config_;
  std::map<int, std::shared_ptr<const Grid>> grids_;
  std::map<int, double> elevations_;  // of every storey of the A-Graph, for the reasons
};

}  // namespace matching
}  // namespace is_graphs
