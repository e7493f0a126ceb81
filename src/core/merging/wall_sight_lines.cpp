#include "wall_sight_lines.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace is_graphs {
namespace merging {
namespace detail {
namespace {

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace

bool Through(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& s,
             const Eigen::Vector2d& e, const std::vector<Gap>& gaps) {
  const Eigen::Vector2d r = q - p, w = e - s;
  const double denom = Cross(r, w);
  if (std::abs(denom) < 1e-12) return false;
  const double t = Cross(s - p, w) / denom;  // along p-q
  const double u = Cross(s - p, r) / denom;  // along s-e
  const double length = w.norm();
  if (t <= 0.0 || t >= 1.0 || u * length < 0.1 || (1.0 - u) * length < 0.1) return false;
  const Eigen::Vector2d x = s + u * w;
  for (const Gap& g : gaps)
    if ((x - g.at).norm() <= g.reach) return false;
  return true;
}

std::vector<PlaneInB> PlanesInB(const sgraph::SGraph& graph, const Eigen::Isometry3d& bim_T_map) {
  std::map<int, Eigen::Vector2d> keyframes;
  for (const auto& k : graph.keyframes)
    keyframes[k.id] = (bim_T_map * k.pose.translation()).head<2>();
  std::map<int, std::vector<Eigen::Vector2d>> seen_from;
  std::map<int, std::set<int>> views;
  for (const auto& o : graph.observations) {
    if (!keyframes.count(o.keyframe)) continue;
    seen_from[o.plane].push_back(keyframes[o.keyframe]);
    views[o.plane].insert(o.keyframe);
  }
  std::vector<PlaneInB> out;
  for (const auto& plane : graph.planes) {
    const geometry::Plane b = plane.plane.Transformed(bim_T_map);
    const double horizontal = b.normal.head<2>().norm();
    if (std::abs(b.normal.z()) >= 0.3 || horizontal < 1e-6) continue;
    PlaneInB p;
    p.id = plane.id;
    p.normal = b.normal.head<2>() / horizontal;
    p.d = b.d / horizontal;
    p.start = (bim_T_map * Eigen::Vector3d(plane.start.x(), plane.start.y(), 0.0)).head<2>();
    p.end = (bim_T_map * Eigen::Vector3d(plane.end.x(), plane.end.y(), 0.0)).head<2>();
    // The extent onto the plane (the stored one may sit a little off it).
    p.start -= (p.normal.dot(p.start) - p.d) * p.normal;
    p.end -= (p.normal.dot(p.end) - p.d) * p.normal;
    p.height = plane.z_max - plane.z_min;
    p.offset_variance = plane.covariance(3, 3);
    const auto& all = seen_from[plane.id];
    p.views = static_cast<int>(views[plane.id].size());
    const size_t n = std::min<size_t>(8, all.size());
    for (size_t i = 0; i < n; ++i) p.from.push_back(all[i * all.size() / n]);
    out.push_back(p);
  }
  return out;
}

std::vector<PathStep> WalkedPathInB(const sgraph::SGraph& graph,
                                    const Eigen::Isometry3d& bim_T_map) {
  std::map<int, Eigen::Vector2d> at;
  for (const auto& k : graph.keyframes) at[k.id] = (bim_T_map * k.pose.translation()).head<2>();
  std::vector<PathStep> out;
  for (const auto& k : graph.keyframes) {
    if (!at.count(k.previous)) continue;
    const Eigen::Vector2d a = at[k.previous], b = at[k.id];
    if ((b - a).norm() <= 2.0) out.emplace_back(a, b);
  }
  return out;
}

double RobotHeight(const sgraph::SGraph& graph, const Eigen::Isometry3d& bim_T_map) {
  std::vector<double> heights;
  for (const auto& k : graph.keyframes) heights.push_back((bim_T_map * k.pose.translation()).z());
  if (heights.empty()) return 0.0;
  std::nth_element(heights.begin(), heights.begin() + heights.size() / 2, heights.end());
  return heights[heights.size() / 2];
}

int RaysThrough(const Eigen::Vector2d& start, const Eigen::Vector2d& end,
                const std::vector<Gap>& gaps, const std::vector<PlaneInB>& planes,
                const std::vector<PathStep>& path) {
  int count = 0;
  for (const auto& [a, b] : path) count += Through(a, b, start, end, gaps) ? 1 : 0;
  for (const auto& p : planes) {
    if (p.from.empty()) continue;
    const double length = p.Length();
    const int n = std::clamp(static_cast<int>(length / 0.3), 1, 16);
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d q = p.start + (i + 0.5) / n * (p.end - p.start) + 0.2 * p.normal;
      size_t through = 0;
      for (const auto& v : p.from) through += Through(v, q, start, end, gaps) ? 1 : 0;
      count += 2 * through >= p.from.size() ? 1 : 0;
    }
  }
  return count;
}

}  // namespace detail
}  // namespace merging
}  // namespace is_graphs
