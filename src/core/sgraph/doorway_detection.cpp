#include "is_graphs/sgraph/doorway_detection.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

namespace is_graphs {
namespace sgraph {
namespace {

/// A wall plane's horizontal line: {x : normal . x = d}, its extent from start along dir.
struct WallLine {
  int id{0};
  Eigen::Vector2d normal, start, dir;
  double d{0.0};
  double length{0.0};
  double floor{0.0};
  double Side(const Eigen::Vector2d& x) const { return normal.dot(x) - d; }
  double Along(const Eigen::Vector2d& x) const { return dir.dot(x - start); }
};

std::vector<WallLine> WallLines(const SGraph& graph, const DoorwayConfig& config) {
  std::vector<WallLine> out;
  for (const auto& p : graph.planes) {
    const Eigen::Vector3d& n = p.plane.normal;
    const double h = n.head<2>().norm();
    if (!n.allFinite() || !std::isfinite(p.plane.d) || h < 0.9) continue;
    if (p.z_max - p.z_min < config.min_wall_height) continue;
    WallLine w;
    w.id = p.id;
    w.normal = n.head<2>() / h;
    const double z = 0.5 * (p.z_min + p.z_max);
    w.d = (p.plane.d - n.z() * z) / h;
    // The extent, projected onto the line (start and end lie on it up to noise).
    const Eigen::Vector2d a = p.start - w.Side(p.start) * w.normal;
    const Eigen::Vector2d b = p.end - w.Side(p.end) * w.normal;
    w.length = (b - a).norm();
    if (!a.allFinite() || !b.allFinite() || w.length < 1e-3) continue;
    w.start = a, w.dir = (b - a) / w.length;
    w.floor = p.z_min;
    out.push_back(w);
  }
  return out;
}

/// The gap (width, > 0) between `wall` and a collinear piece beyond its extent where `u` lies
/// (u along `wall`), or 0 when no piece closes it within max_width.
double GapToCollinearPiece(const WallLine& wall, double u, const std::vector<WallLine>& walls,
                           const DoorwayConfig& config) {
  const bool before = u < 0.0;
  const double edge = before ? 0.0 : wall.length;
  double best = std::numeric_limits<double>::infinity();
  for (const auto& other : walls) {
    if (other.id == wall.id || other.normal.dot(wall.normal) < std::cos(5.0 * M_PI / 180.0))
      continue;
    const Eigen::Vector2d oa = other.start, ob = other.start + other.length * other.dir;
    if (std::abs(wall.Side(oa)) > config.wall_band || std::abs(wall.Side(ob)) > config.wall_band)
      continue;
    const double ua = wall.Along(oa), ub = wall.Along(ob);
    // Its end nearest the gap, on the far side of u.
    const double near = before ? std::max(ua, ub) : std::min(ua, ub);
    if (before ? near < u : near > u) best = std::min(best, std::abs(edge - near));
  }
  return best <= config.max_width ? best : 0.0;
}

struct Crossing {
  const WallLine* wall;
  Eigen::Vector2d at;
  int keyframe{0};  // before the step
  double width{0.0};
};

}  // namespace

std::vector<Doorway> DetectDoorways(const SGraph& graph, const DoorwayConfig& config) {
  if (!config.detect) return {};
  const std::vector<WallLine> walls = WallLines(graph, config);
  std::map<int, const Keyframe*> by_id;
  for (const auto& k : graph.keyframes) by_id[k.id] = &k;

  std::vector<Crossing> crossings;
  for (const auto& k : graph.keyframes) {
    const auto prev = by_id.find(k.previous);
    if (k.previous < 0 || prev == by_id.end()) continue;
    const Eigen::Vector2d a = prev->second->pose.translation().head<2>();
    const Eigen::Vector2d b = k.pose.translation().head<2>();
    if (!a.allFinite() || !b.allFinite() || (b - a).norm() > config.max_step) continue;
    for (const auto& w : walls) {
      const double sa = w.Side(a), sb = w.Side(b);
      if (sa * sb >= 0.0) continue;
      const Eigen::Vector2d x = a + sa / (sa - sb) * (b - a);
      const double u = w.Along(x);
      double width = 0.0;
      if (u < -config.extent_margin || u > w.length + config.extent_margin) {
        width = GapToCollinearPiece(w, u, walls, config);
        if (width <= 0.0) continue;
      }
      crossings.push_back({&w, x, k.previous, width});
    }
  }

  // One doorway per cluster of crossings, in the order they were first walked.
  struct Cluster {
    Eigen::Vector2d sum{Eigen::Vector2d::Zero()};
    int count{0};
    double floor{std::numeric_limits<double>::infinity()};
    double width_sum{0.0};
    int widths{0};
    std::set<int> planes, keyframes;
    int first_keyframe{0};
    const WallLine* wall{nullptr};  // of the first crossing: tells the doorway's two sides
    Eigen::Vector2d Mean() const { return sum / count; }
  };
  std::vector<Cluster> clusters;
  for (const auto& c : crossings) {
    Cluster* into = nullptr;
    for (auto& cl : clusters)
      if ((cl.Mean() - c.at).norm() < config.merge_distance) into = &cl;
    if (!into) {
      clusters.emplace_back();
      into = &clusters.back();
      into->first_keyframe = c.keyframe;
      into->wall = c.wall;
    }
    into->sum += c.at, ++into->count;
    into->floor = std::min(into->floor, c.wall->floor);
    if (c.width > 0.0) into->width_sum += c.width, ++into->widths;
    into->planes.insert(c.wall->id);
    into->keyframes.insert(c.keyframe);
  }

  std::vector<Doorway> out;
  std::map<int, int> rank;  // per first keyframe
  for (const auto& cl : clusters) {
    Doorway d;
    const Eigen::Vector2d m = cl.Mean();
    // On either side of the wall, the nearest room owning a crossed plane (a face along several
    // rooms, one plane in each, is owned by all of them).
    const Room* side[2] = {nullptr, nullptr};
    for (const auto& r : graph.rooms) {
      if (!r.center.allFinite() || std::none_of(r.planes.begin(), r.planes.end(),
                                                [&](int p) { return cl.planes.count(p) > 0; }))
        continue;
      const Eigen::Vector2d c = r.center.head<2>();
      const Room*& best = side[cl.wall->Side(c) < 0.0 ? 0 : 1];
      if (!best || (c - m).norm() < (best->center.head<2>() - m).norm()) best = &r;
    }
    for (const Room* r : side)
      if (r) d.rooms.push_back(r->id);
    if (d.rooms.empty()) continue;
    std::sort(d.rooms.begin(), d.rooms.end());
    d.id = 16 * cl.first_keyframe + std::min(rank[cl.first_keyframe]++, 15);
    d.position = Eigen::Vector3d(m.x(), m.y(), cl.floor);
    d.width = cl.widths > 0 ? cl.width_sum / cl.widths : 0.0;
    d.planes.assign(cl.planes.begin(), cl.planes.end());
    d.keyframes.assign(cl.keyframes.begin(), cl.keyframes.end());
    out.push_back(std::move(d));
  }
  return out;
}

double GapWidth(const std::vector<double>& along, double max_width) {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  for (double u : along) {
    if (!std::isfinite(u)) continue;
    if (u < 0.0)
      lo = std::max(lo, u);
    else
      hi = std::min(hi, u);
  }
  const double width = hi - lo;
  return std::isfinite(width) && width <= max_width ? width : 0.0;
}

}  // namespace sgraph
}  // namespace is_graphs
