#include "is_graphs/matching/scan_search.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <queue>
#include <sstream>
#include <tuple>

#include "is_graphs/matching/scan_grid.h"

namespace is_graphs {
namespace matching {

struct ScanSearch::Grid {
  ScanGrid cells;
};

namespace {

constexpr int kPyramidLevels = 9;       // windows up to 256 cells; nodes up to level 7
constexpr long kRootsWanted = 4096;     // the top node level: the first with fewer roots
constexpr long kMaxNodes = 1'000'000;   // beyond: kTooMany (a flat score, never a guess)
constexpr size_t kMaxLeaves = 200'000;  // leaves within the margin kept at once

// "" when lo < value <= hi (lo_open) or lo <= value <= hi, else a message naming the key.
std::string Check(const char* name, double value, double lo, double hi, bool lo_open,
                  const char* unit) {
  const bool ok = std::isfinite(value) && (lo_open ? value > lo : value >= lo) && value <= hi;
  if (ok) return "";
  std::ostringstream out;
  out << "scan_search_" << name << " " << value << " out of range " << (lo_open ? "(" : "[") << lo
      << ".." << hi << unit << "]";
  return out.str();
}

struct Queued {
  double bound;
  ScanProblem::Node node;
  bool operator<(const Queued& o) const { return bound < o.bound; }  // max-heap on the bound
};

struct Leaf {
  double score;
  int x, y, yaw;
};

}  // namespace

std::string ScanSearchConfig::Validate() const {
  const struct {
    const char* name;
    double value, lo, hi;
    bool lo_open;
    const char* unit;
  } fields[] = {
      {"resolution", resolution, 0.01, 1.0, true, " m"},
      {"sigma", sigma, 0.005, 2.0, true, " m"},
      {"band_low", band_low, -10.0, 10.0, false, " m"},
      {"band_high", band_high, band_low, 20.0, true, " m"},
      {"angular_step_deg", angular_step_deg, 0.0, 10.0, false, " deg"},
      {"margin", margin, 0.0, 1.0, false, ""},
      {"max_set", static_cast<double>(max_set), 1.0, 1e5, false, ""},
      {"min_points", static_cast<double>(min_points), 3.0, 1e7, false, ""},
      {"distinct_xy", distinct_xy, 0.0, 100.0, true, " m"},
      {"distinct_yaw_deg", distinct_yaw_deg, 0.0, 180.0, true, " deg"},
      {"window_margin", window_margin, 0.0, 100.0, false, " m"},
  };
  for (const auto& f : fields) {
    const std::string why = Check(f.name, f.value, f.lo, f.hi, f.lo_open, f.unit);
    if (!why.empty()) return why;
  }
  if (angular_step_deg > 0.0 && angular_step_deg < 0.01)
    return Check("angular_step_deg", angular_step_deg, 0.01, 10.0, false, " deg (or 0)");
  return "";
}

ScanSearch::ScanSearch(const agraph::AGraph& graph, const ScanSearchConfig& config)
    : config_(config) {
  for (const agraph::Storey& st : graph.storeys) {
    elevations_[st.id] = st.elevation;
    const double lo = st.elevation + config.band_low, hi = st.elevation + config.band_high;
    std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> segments;
    for (const agraph::WallSurface& s : graph.surfaces)
      if (s.storey == st.id && s.z_min <= hi && s.z_max >= lo && s.start.allFinite() &&
          s.end.allFinite())
        segments.emplace_back(s.start, s.end);
    if (segments.empty()) continue;
    grids_[st.id] = std::make_shared<const Grid>(
        Grid{ScanGrid(segments, config.resolution, config.sigma, kPyramidLevels)});
  }
}

bool ScanSearch::HasWalls(int storey) const { return grids_.count(storey) > 0; }

bool ScanSearch::TranslationCells(int storey, Eigen::Vector2i* first, Eigen::Vector2i* last) const {
  const auto it = grids_.find(storey);
  if (it == grids_.end()) return false;
  const int m = static_cast<int>(std::ceil(config_.window_margin / config_.resolution - 1e-9));
  *first = it->second->cells.walls_min() - Eigen::Vector2i::Constant(m);
  *last = it->second->cells.walls_max() + Eigen::Vector2i::Constant(m);
  return true;
}

std::unique_ptr<ScanProblem> ScanSearch::Problem(const std::vector<Eigen::Vector2d>& points,
                                                 int storey) const {
  const auto it = grids_.find(storey);
  if (it == grids_.end()) return nullptr;
  auto problem = std::make_unique<ScanProblem>(it->second->cells, points,
                                               config_.angular_step_deg * M_PI / 180.0);
  if (problem->points().empty()) return nullptr;
  return problem;
}

double ScanSearch::Score(const std::vector<Eigen::Vector2d>& points, const Pose2& bim_T_map,
                         int storey) const {
  const auto it = grids_.find(storey);
  if (it == grids_.end()) return 0.0;
  const ScanGrid& grid = it->second->cells;
  const auto thinned = ScanProblem::Thin(points, config_.resolution);
  if (thinned.empty()) return 0.0;
  double sum = 0.0;
  for (const auto& p : thinned) {
    const Eigen::Vector2i c = grid.CellOf(bim_T_map.Apply(p));
    sum += grid.At(0, c.x(), c.y());
  }
  return sum / static_cast<double>(thinned.size());
}

ScanSearchResult ScanSearch::Search(const std::vector<Eigen::Vector2d>& points, int storey) const {
  const auto start = std::chrono::steady_clock::now();
  ScanSearchResult result;
  result.margin = config_.margin;
  auto finish = [&](ScanSearchResult::Status status, const std::string& reason) {
    result.status = status;
    result.reason = reason;
    if (status != ScanSearchResult::Status::kOk) result.set.clear();
    result.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return result;
  };
  std::ostringstream why;
  if (!HasWalls(storey)) {
    const auto e = elevations_.find(storey);
    if (e == elevations_.end())
      why << "storey " << storey << " is not in the A-Graph";
    else
      why << "storey " << storey << " has no wall-surface spanning any of ["
          << e->second + config_.band_low << ", " << e->second + config_.band_high << "] m (band "
          << config_.band_low << ".." << config_.band_high << " m above its elevation " << e->second
          << " m)";
    return finish(ScanSearchResult::Status::kNoWalls, why.str());
  }
  const auto problem = Problem(points, storey);
  const int n = problem ? static_cast<int>(problem->points().size()) : 0;
  if (n < config_.min_points) {
    why << n << " points (one per " << config_.resolution << " m cell, of " << points.size()
        << " given) < min_points " << config_.min_points;
    return finish(ScanSearchResult::Status::kTooFewPoints, why.str());
  }
  const ScanProblem& p = *problem;

  Eigen::Vector2i first, last;
  TranslationCells(storey, &first, &last);
  const Eigen::Vector2i extent = last - first + Eigen::Vector2i::Ones();

  // The top level: the first whose roots are few enough (or the pyramid's last).
  int top = 0;
  auto roots = [&](int l) {
    const long w = 1L << l, k = 1L << p.yaw_level(l);
    return ((extent.x() + w - 1) / w) * ((extent.y() + w - 1) / w) * ((p.yaw_steps() + k - 1) / k);
  };
  while (top < p.max_level() && roots(top) > kRootsWanted) ++top;

  // Best-first: a node is expanded only while its bound is within the margin of the best leaf
  // so far, so every node whose bound reaches final best - margin is expanded: the certificate.
  std::priority_queue<Queued> queue;
  std::vector<Leaf> leaves;
  double best = -1.0;
  size_t filtered_at = 1024;
  auto visit = [&](const ScanProblem::Node& node) {
    const double bound = p.Bound(node, best - config_.margin);
    ++result.nodes;
    if (node.level > 0) {
      if (bound >= best - config_.margin) queue.push({bound, node});
      return;
    }
    best = std::max(best, bound);
    if (bound >= best - config_.margin) leaves.push_back({bound, node.x, node.y, node.yaw});
    if (leaves.size() > 2 * filtered_at) {  // drop the leaves the best has left behind
      leaves.erase(std::remove_if(leaves.begin(), leaves.end(),
                                  [&](const Leaf& l) { return l.score < best - config_.margin; }),
                   leaves.end());
      filtered_at = std::max(filtered_at, leaves.size());
    }
  };
  const int step_top = 1 << p.yaw_level(top);
  for (int yaw = 0; yaw < p.yaw_steps(); yaw += step_top)
    for (int y = first.y(); y <= last.y(); y += 1 << top)
      for (int x = first.x(); x <= last.x(); x += 1 << top) visit({x, y, yaw, top});
  while (!queue.empty()) {
    const Queued q = queue.top();
    queue.pop();
    if (q.bound < best - config_.margin) break;  // so are all that remain
    if (result.nodes > kMaxNodes || leaves.size() > kMaxLeaves) {
      why << "the search gave up after " << result.nodes << " nodes and " << leaves.size()
          << " leaves within the margin " << config_.margin << " (a score this flat has too many"
          << " poses)";
      result.best = best;
      return finish(ScanSearchResult::Status::kTooMany, why.str());
    }
    const int l = q.node.level - 1, half = 1 << l;
    const int yaw_end = std::min(q.node.yaw + (1 << p.yaw_level(l + 1)), p.yaw_steps());
    for (int yaw = q.node.yaw; yaw < yaw_end; yaw += 1 << p.yaw_level(l))
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          const int x = q.node.x + dx * half, y = q.node.y + dy * half;
          if (x <= last.x() && y <= last.y()) visit({x, y, yaw, l});
        }
  }
  result.best = best;

  // The leaves within the margin of the final best, best first, one pose per cluster: a leaf
  // within distinct_xy and distinct_yaw_deg of a representative (its cluster's best) joins it.
  leaves.erase(std::remove_if(leaves.begin(), leaves.end(),
                              [&](const Leaf& l) { return l.score < best - config_.margin; }),
               leaves.end());
  std::sort(leaves.begin(), leaves.end(), [](const Leaf& a, const Leaf& b) {
    return a.score != b.score ? a.score > b.score
                              : std::tie(a.yaw, a.x, a.y) < std::tie(b.yaw, b.x, b.y);
  });
  const double r = config_.resolution, d = config_.distinct_xy;
  const double dyaw = config_.distinct_yaw_deg * M_PI / 180.0;
  std::vector<Leaf> reps;
  std::map<std::pair<long, long>, std::vector<int>> buckets;  // reps by distinct_xy cell
  for (const Leaf& leaf : leaves) {
    const Eigen::Vector2d at(leaf.x * r, leaf.y * r);
    const long bx = static_cast<long>(std::floor(at.x() / d));
    const long by = static_cast<long>(std::floor(at.y() / d));
    int joined = -1;
    for (long i = bx - 1; i <= bx + 1; ++i)
      for (long j = by - 1; j <= by + 1; ++j) {
        const auto b = buckets.find({i, j});
        if (b == buckets.end()) continue;
        for (int k : b->second) {
          const Leaf& rep = reps[k];
          if ((joined < 0 || k < joined) &&
              (Eigen::Vector2d(rep.x * r, rep.y * r) - at).norm() < d &&
              AngleDistance(rep.yaw * p.yaw_step(), leaf.yaw * p.yaw_step()) < dyaw)
            joined = k;
        }
      }
    if (joined >= 0) continue;
    buckets[{bx, by}].push_back(static_cast<int>(reps.size()));
    reps.push_back(leaf);
  }
  if (static_cast<int>(reps.size()) > config_.max_set) {
    why << reps.size() << " distinct poses within the margin " << config_.margin
        << " of the best score " << best << " > max_set " << config_.max_set;
    return finish(ScanSearchResult::Status::kTooMany, why.str());
  }
  for (const Leaf& rep : reps) result.set.push_back({p.LeafPose(rep.x, rep.y, rep.yaw), rep.score});
  return finish(ScanSearchResult::Status::kOk, "");
}

}  // namespace matching
}  // namespace is_graphs
