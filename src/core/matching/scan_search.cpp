// The certified scan search (scan_search.h): per storey a ScanGrid; per search the points
// centred and thinned, rotated once per yaw into cell offsets (Cartographer's discrete scans);
// a depth-first branch and bound over the centre's cell per yaw, children best first, pruned
// below the best so far less the margin; the leaves within the margin clustered into poses.
#include "is_graphs/matching/scan_search.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <unordered_set>

#include "is_graphs/matching/scan_grid.h"

namespace is_graphs {
namespace matching {

struct ScanSearch::Grid {
  ScanGrid grid;
};

namespace {

constexpr int kLevels = 7;  // the roots: squares of 64 cells (3.2 m at 0.05 m)
constexpr int kTop = kLevels - 1;
constexpr int kMaxPoints = 256;        // the points scored (thinned evenly beyond)
constexpr long kMaxNodes = 1000000;    // more nodes scored: too many to certify (bounded cost)
constexpr size_t kMaxLeaves = 200000;  // more leaves within the margin: too many

std::string Range(const char* key, double value, const char* range) {
  std::ostringstream s;
  s << "scan_search_" << key << " " << value << " out of range " << range;
  return s.str();
}

struct Node {
  int yaw, x, y, level;
  int bound;  // Σ over the points of the level's values (0..255 each)
};

}  // namespace

std::string ScanSearchConfig::Validate() const {
  if (!(resolution >= 0.01 && resolution <= 1.0))
    return Range("resolution", resolution, "[0.01, 1] m");
  if (!(sigma >= resolution * 0.5 && sigma <= 2.0))
    return Range("sigma", sigma, "[resolution / 2, 2] m");
  if (!(band_low >= -10.0 && band_low < band_high && band_high <= 20.0))
    return Range("band_low", band_low, "[-10, band_high) m");
  if (!(angular_step_deg >= 0.0 && angular_step_deg <= 10.0))
    return Range("angular_step_deg", angular_step_deg, "[0, 10] deg");
  if (!(margin > 0.0 && margin < 1.0)) return Range("margin", margin, "(0, 1)");
  if (!(max_set >= 1 && max_set <= 10000)) return Range("max_set", max_set, "[1, 10000]");
  if (!(min_points >= 3 && min_points <= 100000))
    return Range("min_points", min_points, "[3, 100000]");
  if (!(distinct_xy > 0.0 && distinct_xy <= 100.0))
    return Range("distinct_xy", distinct_xy, "(0, 100] m");
  if (!(distinct_yaw_deg > 0.0 && distinct_yaw_deg <= 180.0))
    return Range("distinct_yaw_deg", distinct_yaw_deg, "(0, 180] deg");
  if (!(window_margin >= 0.0 && window_margin <= 100.0))
    return Range("window_margin", window_margin, "[0, 100] m");
  return "";
}

ScanSearch::ScanSearch(const agraph::AGraph& graph, const ScanSearchConfig& config)
    : config_(config) {
  for (const agraph::Storey& st : graph.storeys) {
    std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> segments;
    for (const agraph::WallSurface& s : graph.surfaces)
      if (s.storey == st.id && s.z_max >= st.elevation + config.band_low &&
          s.z_min <= st.elevation + config.band_high)
        segments.emplace_back(s.start, s.end);
    auto grid = std::make_shared<Grid>();
    grid->grid = ScanGrid(segments, config.resolution, config.sigma, kLevels);
    grids_[st.id] = std::move(grid);
  }
}

bool ScanSearch::HasWalls(int storey) const {
  const auto it = grids_.find(storey);
  return it != grids_.end() && !it->second->grid.empty();
}

double ScanSearch::Score(const std::vector<Eigen::Vector2d>& points, const Pose2& bim_T_map,
                         int storey) const {
  if (!HasWalls(storey) || points.empty()) return 0.0;
  const ScanGrid& g = grids_.at(storey)->grid;
  long sum = 0;
  for (const auto& p : points) {
    const Eigen::Vector2i c = g.Cell(bim_T_map.Apply(p));
    sum += g.At(0, c.x(), c.y());
  }
  return sum / (255.0 * points.size());
}

ScanSearchResult ScanSearch::Search(const std::vector<Eigen::Vector2d>& points, int storey) const {
  const auto t0 = std::chrono::steady_clock::now();
  ScanSearchResult out;
  out.margin = config_.margin;
  auto done = [&](ScanSearchResult::Status status, const std::string& reason) {
    out.status = status;
    out.reason = reason;
    if (status != ScanSearchResult::Status::kOk) out.set.clear();
    out.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return out;
  };
  if (!HasWalls(storey)) {
    std::ostringstream why;
    why << "storey " << storey << " has no wall-surface between " << config_.band_low << " and "
        << config_.band_high << " m above its elevation";
    return done(ScanSearchResult::Status::kNoWalls, why.str());
  }
  const ScanGrid& g = grids_.at(storey)->grid;
  const double res = g.resolution();
  // The points centred on their mean, one per cell of the grid, at most kMaxPoints.
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const auto& p : points) centre += p;
  if (!points.empty()) centre /= static_cast<double>(points.size());
  std::vector<Eigen::Vector2d> local;
  std::unordered_set<long long> taken;
  for (const auto& p : points) {
    const Eigen::Vector2d q = p - centre;
    const long long key = (static_cast<long long>(std::floor(q.x() / res)) << 32) ^
                          (static_cast<long long>(std::floor(q.y() / res)) & 0xffffffffLL);
    if (taken.insert(key).second) local.push_back(q);
  }
  if (static_cast<int>(local.size()) < config_.min_points) {
    std::ostringstream why;
    why << "too few slice points: " << local.size() << " distinct at " << res << " m (< "
        << config_.min_points << ")";
    return done(ScanSearchResult::Status::kTooFewPoints, why.str());
  }
  if (local.size() > static_cast<size_t>(kMaxPoints)) {
    std::vector<Eigen::Vector2d> thinned;
    for (int k = 0; k < kMaxPoints; ++k) thinned.push_back(local[k * local.size() / kMaxPoints]);
    local.swap(thinned);
  }
  const int n = static_cast<int>(local.size());
  double reach = 0.0;
  for (const auto& q : local) reach = std::max(reach, q.norm());
  double step = config_.angular_step_deg * M_PI / 180.0;
  if (step <= 0.0)
    step = std::acos(1.0 - res * res / (2.0 * std::max(reach, res) * std::max(reach, res)));
  const int yaws = std::max(1, static_cast<int>(std::ceil(2.0 * M_PI / step)));
  step = 2.0 * M_PI / yaws;
  // Each yaw's cell offsets of the points from the centre's cell (Cartographer's discrete
  // scans): a node's bound is the mean of its level's pooled values there.
  std::vector<std::vector<Eigen::Vector2i>> offsets(yaws, std::vector<Eigen::Vector2i>(n));
  for (int k = 0; k < yaws; ++k) {
    const Eigen::Rotation2Dd r(k * step);
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d q = r * local[i] / res;
      offsets[k][i] = {static_cast<int>(std::lround(q.x())), static_cast<int>(std::lround(q.y()))};
    }
  }
  auto bound = [&](int yaw, int x, int y, int level) {
    int sum = 0;
    for (const Eigen::Vector2i& o : offsets[yaw]) sum += g.At(level, x + o.x(), y + o.y());
    return sum;
  };
  // The centre's cells searched: the walls' extent and window_margin around it.
  const int pad = static_cast<int>(std::ceil(config_.window_margin / res));
  const Eigen::Vector2i lo = g.walls().min() - Eigen::Vector2i::Constant(pad);
  const Eigen::Vector2i hi = g.walls().max() + Eigen::Vector2i::Constant(pad);
  const int top = kTop, side = 1 << top;
  std::vector<Node> roots;
  for (int k = 0; k < yaws; ++k)
    for (int y = lo.y(); y <= hi.y(); y += side)
      for (int x = lo.x(); x <= hi.x(); x += side)
        roots.push_back({k, x, y, top, bound(k, x, y, top)});
  out.nodes = static_cast<long>(roots.size());
  std::stable_sort(roots.begin(), roots.end(),
                   [](const Node& a, const Node& b) { return a.bound > b.bound; });
  const int margin = static_cast<int>(std::floor(config_.margin * 255.0 * n));
  int best = -1;
  std::vector<Node> leaves, stack;
  bool overflow = false;
  for (const Node& root : roots) {
    if (root.bound < best - margin) break;  // sorted: no later root can do better
    stack.assign(1, root);
    while (!stack.empty() && !overflow) {
      const Node node = stack.back();
      stack.pop_back();
      if (node.bound < best - margin) continue;
      if (node.level == 0) {
        best = std::max(best, node.bound);
        leaves.push_back(node);
        overflow = leaves.size() > kMaxLeaves;
        continue;
      }
      const int h = node.level - 1, half = 1 << h;
      Node children[4];
      int c = 0;
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          const int x = node.x + dx * half, y = node.y + dy * half;
          if (x > hi.x() || y > hi.y()) continue;
          children[c++] = {node.yaw, x, y, h, bound(node.yaw, x, y, h)};
        }
      out.nodes += c;
      overflow = out.nodes > kMaxNodes;
      // Best child last on the stack: searched first (an insertion sort of at most four).
      for (int i = 1; i < c; ++i)
        for (int k = i; k > 0 && children[k].bound < children[k - 1].bound; --k)
          std::swap(children[k], children[k - 1]);
      for (int i = 0; i < c; ++i)
        if (children[i].bound >= best - margin) stack.push_back(children[i]);
    }
    if (overflow) break;
  }
  if (overflow) {
    std::ostringstream why;
    why << "too many poses fit within the margin to certify: " << out.nodes << " nodes scored, "
        << leaves.size() << " cells within it";
    return done(ScanSearchResult::Status::kTooMany, why.str());
  }
  out.best = best / (255.0 * n);
  // The leaves within the margin of the final best, clustered best first into distinct poses.
  std::stable_sort(leaves.begin(), leaves.end(),
                   [](const Node& a, const Node& b) { return a.bound > b.bound; });
  const double distinct_yaw = config_.distinct_yaw_deg * M_PI / 180.0;
  std::vector<std::pair<Eigen::Vector2d, double>> kept;  // centre in B, yaw
  for (const Node& leaf : leaves) {
    if (leaf.bound < best - margin) break;
    const Eigen::Vector2d c = g.Centre({leaf.x, leaf.y});
    const double yaw = leaf.yaw * step;
    bool same = false;
    for (const auto& [kc, kyaw] : kept)
      if ((kc - c).norm() <= config_.distinct_xy &&
          std::abs(std::remainder(kyaw - yaw, 2.0 * M_PI)) <= distinct_yaw)
        same = true;
    if (same) continue;
    kept.emplace_back(c, yaw);
    if (static_cast<int>(kept.size()) > config_.max_set) {
      std::ostringstream why;
      why << "more than " << config_.max_set << " distinct poses within " << config_.margin
          << " of the best " << out.best;
      return done(ScanSearchResult::Status::kTooMany, why.str());
    }
    ScanPose p;
    p.bim_T_map.yaw = yaw;
    p.bim_T_map.t = c - p.bim_T_map.R() * centre;
    p.score = leaf.bound / (255.0 * n);
    out.set.push_back(p);
  }
  return done(ScanSearchResult::Status::kOk, "");
}

}  // namespace matching
}  // namespace is_graphs
