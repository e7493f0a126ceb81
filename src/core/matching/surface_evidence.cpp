#include "is_graphs/matching/surface_evidence.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include "is_graphs/agraph/agraph_queries.h"

namespace is_graphs {
namespace matching {
namespace {

constexpr double kCell = 1.0;         // m
constexpr double kSampleStep = 0.5;   // m along an S-plane when looking up cells
constexpr double kEndSlack = 0.2;     // m an A-surface's ends are extended by (noise, deviation)
constexpr double kDepthSlack = 0.05;  // m beyond a wall's thickness still in its depth (noise)

long long CellKey(long long ix, long long iy) { return (ix << 32) ^ (iy & 0xffffffffLL); }
long long CellOf(double v) { return static_cast<long long>(std::floor(v / kCell)); }

double Cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

/// The convex hull of `points`, counter-clockwise (Andrew's monotone chain).
std::vector<Eigen::Vector2d> ConvexHull(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& x, const Eigen::Vector2d& y) {
    return x.x() < y.x() || (x.x() == y.x() && x.y() < y.y());
  });
  if (points.size() < 3) return {};
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  size_t k = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && Cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  for (size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && Cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull.size() >= 3 ? hull : std::vector<Eigen::Vector2d>{};
}

}  // namespace

std::vector<WallSegment> WallSegments(const sgraph::SGraph& graph, const MatcherConfig& config) {
  std::vector<WallSegment> out;
  std::set<int> ids;
  for (const auto& p : graph.planes) {
    if (!p.plane.normal.allFinite() || !std::isfinite(p.plane.d) || !p.start.allFinite() ||
        !p.end.allFinite() || !std::isfinite(p.z_min) || !std::isfinite(p.z_max))
      continue;
    const Eigen::Vector2d n = p.plane.normal.head<2>();
    if (n.norm() < 0.95) continue;  // more than ~18 deg from vertical
    const double length = (p.end - p.start).norm();
    if (length < config.surface_min_length || p.z_max - p.z_min < config.surface_min_height)
      continue;
    if (!ids.insert(p.id).second) continue;  // the first of a duplicated id
    out.push_back({p.id, p.start, p.end, n.normalized(), length});
  }
  return out;
}

SurfaceEvidence::SurfaceEvidence(const agraph::AGraph& graph, const MatcherConfig& config)
    : cos_angle_(std::cos(config.angle_tolerance_deg * M_PI / 180.0)),
      offset_tolerance_(config.offset_tolerance),
      full_length_(config.surface_full_length),
      outside_margin_(config.outside_margin) {
  for (const auto& s : graph.surfaces) {
    const Eigen::Vector2d n = s.plane.normal.head<2>();
    if (!s.start.allFinite() || !s.end.allFinite() || !n.allFinite() || n.norm() < 0.5 ||
        s.Length() < 1e-3)
      continue;
    // On its own storey and on those of the rooms it bounds (a wall modelled on one storey
    // may stand up through the next).
    const std::set<int> on = agraph::StoreysOfSurface(graph, s);
    const Eigen::Vector2d unit = n.normalized();
    const double depth = s.wall >= 0 && s.wall < static_cast<int>(graph.walls.size()) &&
                                 std::isfinite(graph.walls[s.wall].thickness)
                             ? std::clamp(graph.walls[s.wall].thickness, 0.0, 1.0)
                             : 0.0;
    const double pad = std::max(offset_tolerance_, depth + kDepthSlack) + kEndSlack;
    const Eigen::Vector2d lo = s.start.cwiseMin(s.end).array() - pad;
    const Eigen::Vector2d hi = s.start.cwiseMax(s.end).array() + pad;
    for (int id : on) {
      Storey& storey = storeys_[id];
      const int index = static_cast<int>(storey.surfaces.size());
      storey.surfaces.push_back(
          {s.id, s.start, s.end, unit, unit.dot(0.5 * (s.start + s.end)), depth});
      // Every cell within offset_tolerance of the segment (its bounding box, widened).
      for (long long ix = CellOf(lo.x()); ix <= CellOf(hi.x()); ++ix)
        for (long long iy = CellOf(lo.y()); iy <= CellOf(hi.y()); ++iy)
          storey.cells[CellKey(ix, iy)].push_back(index);
    }
  }
  for (auto& [id, storey] : storeys_) {
    std::vector<Eigen::Vector2d> ends;
    for (const Surface& s : storey.surfaces) ends.push_back(s.a), ends.push_back(s.b);
    const std::vector<Eigen::Vector2d> hull = ConvexHull(std::move(ends));
    for (size_t i = 0; i < hull.size(); ++i) {
      const Eigen::Vector2d edge = hull[(i + 1) % hull.size()] - hull[i];
      if (edge.norm() < 1e-9) continue;
      const Eigen::Vector2d out = Eigen::Vector2d(edge.y(), -edge.x()).normalized();
      storey.outline.emplace_back(out, out.dot(hull[i]));
    }
  }
}

std::vector<SurfaceEvidence::Along> SurfaceEvidence::AlongSurfaces(const WallSegment& plane,
                                                                   const Pose2& pose,
                                                                   int storey) const {
  return Stretches(plane, pose, storey, false);
}

std::vector<SurfaceEvidence::Along> SurfaceEvidence::InWallDepth(const WallSegment& plane,
                                                                 const Pose2& pose,
                                                                 int storey) const {
  return Stretches(plane, pose, storey, true);
}

std::vector<SurfaceEvidence::Along> SurfaceEvidence::Stretches(const WallSegment& plane,
                                                               const Pose2& pose, int storey,
                                                               bool in_depth) const {
  std::vector<Along> out;
  const auto found = storeys_.find(storey);
  if (found == storeys_.end() || plane.length <= 0.0) return out;
  const Storey& st = found->second;
  const Eigen::Matrix2d rot = pose.R();  // once, not per point
  const Eigen::Vector2d a = rot * plane.a + pose.t, b = rot * plane.b + pose.t;
  const Eigen::Vector2d n = rot * plane.normal;
  const Eigen::Vector2d middle = 0.5 * (a + b);
  const Eigen::Vector2d along = (b - a) / plane.length;
  std::vector<int> candidates;
  const int samples = 1 + static_cast<int>(std::ceil(plane.length / kSampleStep));
  for (int i = 0; i <= samples; ++i) {
    const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(i) / samples);
    const auto cell = st.cells.find(CellKey(CellOf(p.x()), CellOf(p.y())));
    if (cell != st.cells.end())
      candidates.insert(candidates.end(), cell->second.begin(), cell->second.end());
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  for (int i : candidates) {
    const Surface& s = st.surfaces[i];
    if (s.normal.dot(n) < cos_angle_) continue;
    const double offset = s.normal.dot(middle) - s.d;  // < 0: behind the face
    const bool on = std::abs(offset) <= offset_tolerance_;
    const bool deep = offset < -offset_tolerance_ && offset >= -(s.depth + kDepthSlack);
    if (in_depth ? !deep : !on) continue;
    double u0 = (s.a - a).dot(along), u1 = (s.b - a).dot(along);
    if (u0 > u1) std::swap(u0, u1);
    u0 = std::max(u0 - kEndSlack, 0.0);
    u1 = std::min(u1 + kEndSlack, plane.length);
    if (u1 > u0) out.push_back({s.id, s.normal, s.d, 0.5 * (s.a + s.b), u0, u1});
  }
  return out;
}

double SurfaceEvidence::Share(const WallSegment& plane, const Pose2& pose, int storey) const {
  if (plane.length <= 0.0) return 0.0;
  // The stretches of the plane (as distances from a along it) that lie on an A-surface.
  std::vector<std::pair<double, double>> covered;
  for (const Along& s : AlongSurfaces(plane, pose, storey)) covered.emplace_back(s.from, s.to);
  for (const Along& s : InWallDepth(plane, pose, storey)) covered.emplace_back(s.from, s.to);
  std::sort(covered.begin(), covered.end());
  double total = 0.0, reach = 0.0;
  for (const auto& [u0, u1] : covered) {
    const double from = std::max(u0, reach);
    if (u1 > from) total += u1 - from;
    reach = std::max(reach, u1);
  }
  return std::min(1.0, total / plane.length);
}

double SurfaceEvidence::Explained(const std::vector<WallSegment>& planes, const Pose2& pose,
                                  int storey) const {
  double sum = 0.0;
  for (const WallSegment& p : planes)
    sum += std::min(1.0, p.length / full_length_) * Share(p, pose, storey);
  return sum;
}

double SurfaceEvidence::Bound(const std::vector<WallSegment>& planes) const {
  double sum = 0.0;
  for (const WallSegment& p : planes) sum += std::min(1.0, p.length / full_length_);
  return sum;
}

double SurfaceEvidence::Outside(const std::vector<WallSegment>& planes, const Pose2& pose,
                                int storey) const {
  const auto found = storeys_.find(storey);
  if (found == storeys_.end() || found->second.outline.empty()) return 0.0;
  const auto& outline = found->second.outline;
  const Eigen::Matrix2d rot = pose.R();
  double sum = 0.0;
  for (const WallSegment& p : planes) {
    if (p.length <= 0.0) continue;
    const Eigen::Vector2d a = rot * p.a + pose.t, b = rot * p.b + pose.t;
    const int samples = std::max(1, static_cast<int>(std::ceil(p.length / kSampleStep)));
    int outside = 0;
    for (int i = 0; i < samples; ++i) {
      const Eigen::Vector2d q = a + (b - a) * ((i + 0.5) / samples);
      // Beyond an edge's line by more than the margin: farther than that from the hull.
      outside += std::any_of(outline.begin(), outline.end(), [&](const auto& edge) {
        return edge.first.dot(q) - edge.second > outside_margin_;
      });
    }
    sum += std::min(1.0, p.length / full_length_) * outside / samples;
  }
  return sum;
}

}  // namespace matching
}  // namespace is_graphs
