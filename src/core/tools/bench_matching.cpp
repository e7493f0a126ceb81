// bench_matching: matching time of the A-Graph <-> S-Graph matcher for S-Graphs of 3, 10 and 20
// rooms against procedural A-Graphs of 10, 60 and 200 rooms (grid-like, column widths and row
// depths varied so rooms are not all alike, some repeated as in real buildings). Deterministic
// seeds. Prints a Markdown table: median and p90 of a cold match (fresh matcher), of a warm
// re-match (the next revision, nothing changed: incremental reuse) and the share UNIQUE.
//
// The S-Graphs carry the walk through their rooms (keyframes), the doorways found on it and the
// keyframes that observed each plane, as the harsh campaign's do: every kind of evidence.
//
// Then the scan search's cost (BenchScanSearch; --scan-only: that table alone).
//
//   bench_matching [--reps N] [--no-doubt] [--no-proposals] [--rooms-only] [--cell A S]
//                  [--scan-only]
//   (--no-doubt: doubt_centre_tolerance 0, no re-check; --no-proposals: no corner proposals;
//    --rooms-only: S-Graphs of rooms and planes alone, no walk, doorways or observations;
//    --cell A S: only the cell of A A-Graph rooms and S S-Graph rooms)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "is_graphs/matching/graph_matcher.h"
#include "is_graphs/matching/pose_hint.h"
#include "is_graphs/matching/scan_search.h"
#include "is_graphs/matching/synthetic_first_view.h"
#include "is_graphs/matching/synthetic_sgraph.h"

namespace is_graphs {
namespace {

/// A storey of cols × rows rooms between 0.15 m walls; widths and depths from a few values.
agraph::AGraph GridBuilding(int cols, int rows, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> size(0, 14);  // 3.0 .. 6.5 m in 0.25 m steps
  std::vector<double> xs{0.0}, ys{0.0};
  for (int i = 0; i < cols; ++i) xs.push_back(xs.back() + 3.0 + 0.25 * size(rng));
  for (int j = 0; j < rows; ++j) ys.push_back(ys.back() + 3.0 + 0.25 * size(rng));
  agraph::AGraph g;
  g.building = "grid_" + std::to_string(cols * rows);
  g.source.sha256 = g.building;
  g.storeys.push_back({});
  const double h = 0.075;  // half a wall
  auto room_id = [&](int i, int j) { return j * cols + i; };
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      agraph::Room r;
      r.id = room_id(i, j);
      r.name = "R" + std::to_string(r.id);
      const double x0 = xs[i] + h, x1 = xs[i + 1] - h, y0 = ys[j] + h, y1 = ys[j + 1] - h;
      r.polygon = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
      r.z_max = 2.8;
      r.center = Eigen::Vector3d(0.5 * (x0 + x1), 0.5 * (y0 + y1), 1.4);
      r.area = (x1 - x0) * (y1 - y0);
      const struct {
        Eigen::Vector3d n;
        Eigen::Vector2d a, b;
      } faces[] = {{{1, 0, 0}, {x0, y1}, {x0, y0}},
                   {{-1, 0, 0}, {x1, y0}, {x1, y1}},
                   {{0, 1, 0}, {x0, y0}, {x1, y0}},
                   {{0, -1, 0}, {x1, y1}, {x0, y1}}};
      for (const auto& f : faces) {
        agraph::WallSurface s;
        s.id = static_cast<int>(g.surfaces.size());
        s.plane = geometry::Plane::FromPointNormal(Eigen::Vector3d(f.a.x(), f.a.y(), 0.0), f.n);
        s.orientation = geometry::ClassifyOrientation(f.n);
        s.start = f.a, s.end = f.b;
        if ((s.end - s.start).dot(s.Tangent().head<2>()) < 0) std::swap(s.start, s.end);
        s.z_max = 2.8;
        s.rooms = {r.id};
        r.surfaces.push_back(s.id);
        g.surfaces.push_back(s);
      }
      g.rooms.push_back(r);
    }
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i)
      for (const auto& [di, dj] : {std::pair<int, int>{1, 0}, {0, 1}}) {
        if (i + di >= cols || j + dj >= rows) continue;
        agraph::Doorway d;
        d.id = static_cast<int>(g.doorways.size());
        d.rooms = {room_id(i, j), room_id(i + di, j + dj)};
        // In the middle of the wall the two rooms share, 0.9 m wide.
        d.position = di ? Eigen::Vector3d(xs[i + 1], 0.5 * (ys[j] + ys[j + 1]), 0.0)
                        : Eigen::Vector3d(0.5 * (xs[i] + xs[i + 1]), ys[j + 1], 0.0);
        d.width = 0.9;
        d.height = 2.0;
        for (int r : d.rooms) g.rooms[r].doorways.push_back(d.id);
        g.doorways.push_back(d);
      }
  return g;
}

double Percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[std::min(v.size() - 1, static_cast<size_t>(p * (v.size() - 1) + 0.5))];
}

/// The scan search (scan_search.h) on one keyframe's slice from `reps` random rooms of grid
/// storeys of 10, 60 and 200 rooms at the default 0.05 m: grid build time, search time, the
/// set's size and whether the truth is in it.
void BenchScanSearch(int reps) {
  std::printf(
      "\n| A-Graph rooms | grid build ms | search median ms | search max ms | nodes median | "
      "set size median | declined (too many) | truth in the set "
      "|\n|---|---|---|---|---|---|---|---|\n");
  const struct { int cols, rows; } buildings[] = {{5, 2}, {10, 6}, {20, 10}};
  for (const auto& b : buildings) {
    const agraph::AGraph g = GridBuilding(b.cols, b.rows, 1000 + b.cols);
    const auto t0 = std::chrono::steady_clock::now();
    const matching::ScanSearch search(g, matching::ScanSearchConfig{});
    const double build =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::vector<double> ms, nodes, sizes;
    int truth_in = 0, runs = 0, declined = 0;
    std::mt19937_64 rng(4900 + b.cols);
    for (int r = 0; r < reps; ++r) {
      matching::FirstViewConfig c;
      c.room = std::uniform_int_distribution<int>(0, static_cast<int>(g.rooms.size()) - 1)(rng);
      c.bim_T_map = matching::RandomPlanarMotion(rng, 100.0);
      c.seed = rng();
      const matching::SyntheticSGraph view = matching::MakeFirstView(g, c);
      if (view.graph.keyframes.empty()) continue;
      std::vector<Eigen::Vector2d> points;
      const auto& k = view.graph.keyframes.front();
      for (const auto& p : k.slice) points.push_back((k.pose * p.cast<double>()).head<2>());
      const matching::ScanSearchResult res = search.Search(points, 0);
      ++runs;
      if (res.status != matching::ScanSearchResult::Status::kOk) ++declined;
      ms.push_back(res.milliseconds);
      nodes.push_back(static_cast<double>(res.nodes));
      sizes.push_back(static_cast<double>(res.set.size()));
      const matching::Pose2 truth = matching::PlanarPose(view.bim_T_map);
      for (const auto& p : res.set)
        if ((p.bim_T_map.Apply(points.front()) - truth.Apply(points.front())).norm() < 0.15 &&
            std::abs(std::remainder(p.bim_T_map.yaw - truth.yaw, 2.0 * M_PI)) < 0.035) {
          ++truth_in;
          break;
        }
    }
    std::printf("| %zu | %.0f | %.1f | %.1f | %.0f | %.0f | %d | %d/%d |\n", g.rooms.size(), build,
                Percentile(ms, 0.5), Percentile(ms, 1.0), Percentile(nodes, 0.5),
                Percentile(sizes, 0.5), declined, truth_in, runs - declined);
    std::fflush(stdout);
  }
}

}  // namespace
}  // namespace is_graphs

int main(int argc, char** argv) {
  using namespace is_graphs;
  int reps = 30;
  bool walk = true;
  int only_a = 0, only_s = 0;  // --cell A S: that cell alone (for profiling)
  bool scan_only = false;
  matching::MatcherConfig config;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--reps") == 0 && i + 1 < argc)
      reps = std::max(1, std::atoi(argv[++i]));
    else if (std::strcmp(argv[i], "--no-doubt") == 0)
      config.doubt_centre_tolerance = 0.0;
    else if (std::strcmp(argv[i], "--no-proposals") == 0)
      config.proposals = false;
    else if (std::strcmp(argv[i], "--rooms-only") == 0)
      walk = false;
    else if (std::strcmp(argv[i], "--scan-only") == 0)
      scan_only = true;
    else if (std::strcmp(argv[i], "--cell") == 0 && i + 2 < argc)
      only_a = std::atoi(argv[i + 1]), only_s = std::atoi(argv[i + 2]), i += 2;
    else
      return std::fprintf(stderr,
                          "usage: bench_matching [--reps N] [--no-doubt] [--no-proposals] "
                          "[--rooms-only] [--cell A S] [--scan-only]\n"),
             2;
  }
  if (scan_only) {
    BenchScanSearch(reps);
    return 0;
  }
  const struct { int cols, rows; } buildings[] = {{5, 2}, {10, 6}, {20, 10}};
  std::printf(
      "| A-Graph rooms | S-Graph rooms | cold median ms | cold p90 ms | warm median ms | "
      "candidates | seeds | proposals | S-doorways | UNIQUE "
      "|\n|---|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& b : buildings) {
    const agraph::AGraph g = GridBuilding(b.cols, b.rows, 1000 + b.cols);
    for (int s_rooms : {3, 10, 20}) {
      if (s_rooms > static_cast<int>(g.rooms.size())) continue;
      if (only_a > 0 && (only_a != static_cast<int>(g.rooms.size()) || only_s != s_rooms)) continue;
      std::vector<double> cold, warm;
      double candidates = 0, seeds = 0, proposals = 0, doors = 0;
      int unique = 0;
      std::mt19937_64 rng(77 + s_rooms);
      for (int r = 0; r < reps; ++r) {
        matching::SyntheticSGraphConfig c;
        c.rooms = matching::RandomConnectedRooms(g, s_rooms, rng);
        c.bim_T_map = matching::RandomPlanarMotion(rng, 100.0);
        c.normal_noise_deg = 1.0;
        c.offset_noise = 0.03;
        c.centre_noise = 0.1;
        c.bim_deviation = 0.05;
        c.seed = rng();
        // The walk through the rooms' doorways, the doorways found on it and the keyframes
        // that saw each plane: every kind of evidence the matcher weighs.
        c.walk = walk;
        c.doorways = walk;
        c.observations = walk;
        matching::SyntheticSGraph s = matching::MakeSyntheticSGraph(g, c);
        matching::GraphMatcher matcher(config);
        matcher.SetAGraph(g);
        const auto m = matcher.Match(s.graph);
        cold.push_back(matcher.LastStats().milliseconds);
        candidates += matcher.LastStats().candidates;
        seeds += matcher.LastStats().seeds;
        proposals += matcher.LastStats().proposals;
        doors += static_cast<double>(s.graph.doorways.size());
        unique += m.status == matching::MatchStatus::kUnique;
        s.graph.revision += 1;
        matcher.Match(s.graph);
        warm.push_back(matcher.LastStats().milliseconds);
      }
      std::printf("| %zu | %d | %.2f | %.2f | %.2f | %.0f | %.0f | %.0f | %.1f | %d/%d |\n",
                  g.rooms.size(), s_rooms, Percentile(cold, 0.5), Percentile(cold, 0.9),
                  Percentile(warm, 0.5), candidates / reps, seeds / reps, proposals / reps,
                  doors / reps, unique, reps);
      std::fflush(stdout);
    }
  }
  if (only_a == 0) BenchScanSearch(reps);
  return 0;
}
