#include "is_graphs/matching/wall_crossings.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace is_graphs {
namespace matching {
namespace {

constexpr double kCell = 1.0;  // m
// A path through a wall goes across it: from the face it went in by to the other within this
// (a 0.4 m wall crossed at 25 deg to its face). Longer is a path along it, the pose's error.
constexpr double kMaxTraversal = 1.0;  // m

long long CellKey(long long ix, long long iy) { return (ix << 32) ^ (iy & 0xffffffffLL); }

long long CellOf(double v) { return static_cast<long long>(std::floor(v / kCell)); }

double Cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
  return u.x() * v.y() - u.y() * v.x();
}

/// The point where segments p0-p1 and q0-q1 cross, if they do (touching ends count).
bool Intersect(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Eigen::Vector2d& q0,
               const Eigen::Vector2d& q1, Eigen::Vector2d* at) {
  const Eigen::Vector2d r = p1 - p0, s = q1 - q0;
  const double denom = Cross(r, s);
  if (std::abs(denom) < 1e-12) return false;  // parallel: walking along a wall crosses nothing
  const double u = Cross(q0 - p0, s) / denom;
  const double v = Cross(q0 - p0, r) / denom;
  if (u < 0.0 || u > 1.0 || v < 0.0 || v > 1.0) return false;
  *at = p0 + u * r;
  return true;
}

}  // namespace

std::vector<PathStep> WalkedPath(const sgraph::SGraph& graph, double max_step) {
  std::map<int, Eigen::Vector2d> position;
  for (const auto& k : graph.keyframes)
    if (k.pose.translation().allFinite()) position.emplace(k.id, k.pose.translation().head<2>());
  std::vector<PathStep> steps;
  for (const auto& k : graph.keyframes) {
    const auto it = position.find(k.id), prev = position.find(k.previous);
    if (k.previous < 0 || it == position.end() || prev == position.end()) continue;
    if ((it->second - prev->second).norm() > max_step) continue;
    steps.emplace_back(prev->second, it->second);
  }
  return steps;
}

WallCrossings::WallCrossings(const agraph::AGraph& graph, double door_margin, double sight_margin) {
  std::set<int> bounds_room;  // surface ids some room lists
  for (const auto& r : graph.rooms) bounds_room.insert(r.surfaces.begin(), r.surfaces.end());
  for (const auto& s : graph.surfaces) {
    if (!s.start.allFinite() || !s.end.allFinite() || s.Length() < 1e-6) continue;
    Storey& storey = storeys_[s.storey];
    const int index = static_cast<int>(storey.surfaces.size());
    const Eigen::Vector2d n = s.plane.normal.head<2>();
    const bool faced = n.norm() > 0.5;  // no direction (not a wall): crossed wherever it is
    storey.surfaces.push_back({s.start, s.end, faced ? n.normalized() : Eigen::Vector2d::Zero(),
                               s.wall >= 0 && faced ? s.wall : -1 - s.id, false,
                               bounds_room.count(s.id) > 0});
    // Every cell the surface's segment passes through (sampled finer than a cell).
    std::set<long long> keys;
    const int samples = 1 + static_cast<int>(std::ceil(4.0 * s.Length() / kCell));
    for (int i = 0; i <= samples; ++i) {
      const Eigen::Vector2d p = s.start + (s.end - s.start) * (static_cast<double>(i) / samples);
      keys.insert(CellKey(CellOf(p.x()), CellOf(p.y())));
    }
    for (long long key : keys) storey.cells[key].push_back(index);
  }
  for (auto& [id, storey] : storeys_) {
    std::map<int, int> faces;   // wall -> surfaces on this storey
    std::map<int, bool> inner;  // wall -> every face bounds a room
    for (const auto& f : storey.surfaces) {
      ++faces[f.wall];
      inner.emplace(f.wall, true).first->second &= f.interior;
    }
    for (auto& f : storey.surfaces) {
      f.two_faced = f.wall >= 0 && faces[f.wall] > 1;
      f.interior = f.two_faced && inner[f.wall];
    }
  }
  for (const auto& d : graph.doorways) {
    // A virtual separation is no gap in a wall: walls near it are walls.
    if (!d.InWall() || !d.position.allFinite() || !std::isfinite(d.width)) continue;
    storeys_[d.storey].doors.push_back({d.position.head<2>(),
                                        0.5 * std::max(d.width, 0.0) + door_margin,
                                        0.5 * std::max(d.width, 0.0) + sight_margin});
  }
}

bool WallCrossings::NearDoor(const Storey& storey, const Eigen::Vector2d& p, bool sight) const {
  return std::any_of(storey.doors.begin(), storey.doors.end(), [&](const Door& d) {
    return (d.position - p).norm() <= (sight ? d.sight_reach : d.reach);
  });
}

int WallCrossings::Count(const std::vector<PathStep>& steps, const Pose2& pose, int storey) const {
  return static_cast<int>(Through(steps, pose, storey, false).size());
}

bool WallCrossings::Blocks(const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                           const Pose2& pose, int storey) const {
  return !Through({{from, to}}, pose, storey, true).empty();
}

std::set<int> WallCrossings::Through(const std::vector<PathStep>& steps, const Pose2& pose,
                                     int storey, bool sight) const {
  const auto found = storeys_.find(storey);
  if (found == storeys_.end()) return {};
  const Storey& s = found->second;
  std::set<int> crossed;
  std::map<int, Entry> inside;  // wall -> where the path went into it (two-faced walls)
  std::vector<int> candidates;
  struct Hit {
    double distance;  // along the step
    int surface;
    Eigen::Vector2d at;
  };
  std::vector<Hit> hits;
  Eigen::Vector2d last(std::nan(""), std::nan(""));
  const Eigen::Matrix2d rot = pose.R();  // once, not per step
  for (const auto& [m0, m1] : steps) {
    if (!(m0 - last).isZero(1e-9)) inside.clear();  // a gap: the path starts anew
    last = m1;
    const Eigen::Vector2d p0 = rot * m0 + pose.t, p1 = rot * m1 + pose.t;
    candidates.clear();
    for (long long ix = CellOf(std::min(p0.x(), p1.x())); ix <= CellOf(std::max(p0.x(), p1.x()));
         ++ix)
      for (long long iy = CellOf(std::min(p0.y(), p1.y())); iy <= CellOf(std::max(p0.y(), p1.y()));
           ++iy) {
        const auto cell = s.cells.find(CellKey(ix, iy));
        if (cell != s.cells.end())
          candidates.insert(candidates.end(), cell->second.begin(), cell->second.end());
      }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    hits.clear();
    for (int i : candidates) {
      Eigen::Vector2d at;
      if (Intersect(p0, p1, s.surfaces[i].a, s.surfaces[i].b, &at))
        hits.push_back({(at - p0).norm(), i, at});
    }
    std::sort(hits.begin(), hits.end(), [](const Hit& x, const Hit& y) {  // in the order walked
      return x.distance != y.distance ? x.distance < y.distance : x.surface < y.surface;
    });
    for (const auto& [distance, i, at] : hits) {
      const Surface& surface = s.surfaces[i];
      if (sight && !surface.interior) continue;
      const bool door = NearDoor(s, at, sight);
      if (!surface.two_faced) {
        if (!door) crossed.insert(surface.wall);
        continue;
      }
      if ((p1 - p0).dot(surface.normal) < 0.0) {  // into the wall's material
        inside[surface.wall] = {i, door, at};
        continue;
      }
      const auto entry = inside.find(surface.wall);  // out of it
      if (entry == inside.end()) continue;
      // Out by the other face: opposed normals (a face split into collinear pieces, in by one
      // piece and out by the next, is the same face).
      const bool other_face = s.surfaces[entry->second.surface].normal.dot(surface.normal) < -0.5;
      if (other_face && !entry->second.near_door && !door &&
          (entry->second.at - at).norm() <= kMaxTraversal) {
        crossed.insert(surface.wall);
        if (sight) return crossed;
      }
      inside.erase(entry);
    }
  }
  return crossed;
}

}  // namespace matching
}  // namespace is_graphs
