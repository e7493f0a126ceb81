#include "is_graphs/matching/corner_proposals.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>

#include "is_graphs/agraph/agraph_queries.h"
#include "is_graphs/geometry/se3.h"

namespace is_graphs {
namespace matching {
namespace {

constexpr double kMaxCos = 0.7072;     // normals at least 45° apart
constexpr double kClusterStep = 0.25;  // m
constexpr double kClusterYaw = 2.0;    // deg
double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

double DistanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                         const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double l2 = ab.squaredNorm();
  const double u = l2 > 0.0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (a + u * ab - p).norm();
}

double Heading(const Eigen::Vector2d& v) { return std::atan2(v.y(), v.x()); }

}  // namespace

std::vector<Corner> FindCorners(const std::vector<FacingSegment>& segments, double reach) {
  std::vector<Corner> out;
  for (size_t i = 0; i < segments.size(); ++i) {
    const FacingSegment& s = segments[i];
    const double length = (s.b - s.a).norm();
    if (!(length >= 2.0 * reach)) continue;
    const Eigen::Vector2d d = (s.b - s.a) / length;
    for (size_t j = 0; j < segments.size(); ++j) {
      const FacingSegment& o = segments[j];
      if (i == j || o.storey != s.storey || std::abs(s.normal.dot(o.normal)) > kMaxCos) continue;
      const Eigen::Vector2d e = o.b - o.a;
      if (e.norm() < 1e-6) continue;
      // Lines s.a + u d and o.a + v e meet at u = cross(o.a - s.a, e) / cross(d, e).
      const double u = Cross(o.a - s.a, e) / Cross(d, e);
      const Eigen::Vector2d x = s.a + u * d;
      const bool at_a = std::abs(u) <= reach, at_b = std::abs(u - length) <= reach;
      if (!(at_a || at_b) || DistanceToSegment(x, o.a, o.b) > reach) continue;
      Corner c;
      c.point = x;
      c.normal = s.normal;
      c.along = at_a ? d : Eigen::Vector2d(-d);
      c.other = o.normal;
      c.storey = s.storey;
      out.push_back(c);
    }
  }
  return out;
}

std::vector<FacingSegment> FacingSurfaces(const agraph::AGraph& graph) {
  std::vector<FacingSegment> out;
  for (const auto& s : graph.surfaces) {
    const Eigen::Vector2d n = s.plane.normal.head<2>();
    if (!s.start.allFinite() || !s.end.allFinite() || !n.allFinite() || n.norm() < 0.5 ||
        s.Length() < 1e-3)
      continue;
    for (int storey : agraph::StoreysOfSurface(graph, s))
      out.push_back({s.start, s.end, n.normalized(), storey});
  }
  return out;
}

std::vector<FacingSegment> FacingWalls(const std::vector<WallSegment>& walls) {
  std::vector<FacingSegment> out;
  for (const auto& w : walls) out.push_back({w.a, w.b, w.normal, -1});
  return out;
}

std::vector<MotionProposal> ProposeMotions(const std::vector<Corner>& seen,
                                           const std::vector<Corner>& bim,
                                           double angle_tolerance_deg, int max_distinct,
                                           bool* too_many) {
  if (too_many) *too_many = false;
  const double tolerance = angle_tolerance_deg * M_PI / 180.0;
  // Headings once per corner: the pairs are checked by angle differences, no trigonometry.
  struct Headings {
    double normal, other, along;
  };
  auto headings = [](const std::vector<Corner>& corners) {
    std::vector<Headings> out;
    out.reserve(corners.size());
    for (const Corner& c : corners)
      out.push_back({Heading(c.normal), Heading(c.other), Heading(c.along)});
    return out;
  };
  const std::vector<Headings> hs = headings(seen), ha = headings(bim);
  std::map<std::tuple<int, long, long, long>, MotionProposal> cells;
  for (size_t i = 0; i < seen.size(); ++i)
    for (size_t j = 0; j < bim.size(); ++j) {
      const Corner &s = seen[i], &a = bim[j];
      const double yaw = ha[j].normal - hs[i].normal;
      const double other_yaw = ha[j].other - hs[i].other;
      if (std::abs(geometry::NormalizeAngle(other_yaw - yaw)) > tolerance ||
          std::abs(geometry::NormalizeAngle(ha[j].along - hs[i].along - yaw)) > tolerance)
        continue;
      // The yaw from both normals, then the translation that puts the corners together.
      Pose2 pose;
      pose.yaw = geometry::NormalizeAngle(yaw + 0.5 * geometry::NormalizeAngle(other_yaw - yaw));
      pose.t = a.point - pose.Rotate(s.point);
      const auto key = std::make_tuple(a.storey, std::lround(pose.t.x() / kClusterStep),
                                       std::lround(pose.t.y() / kClusterStep),
                                       std::lround(pose.yaw * 180.0 / M_PI / kClusterYaw));
      ++cells.try_emplace(key, MotionProposal{pose, a.storey, 0}).first->second.votes;
      if (static_cast<int>(cells.size()) > max_distinct) {
        if (too_many) *too_many = true;
        return {};
      }
    }
  std::vector<MotionProposal> out;
  out.reserve(cells.size());
  for (auto& [key, p] : cells) out.push_back(p);
  // std::map order is deterministic; a stable sort by votes keeps it among equals.
  std::stable_sort(out.begin(), out.end(), [](const MotionProposal& x, const MotionProposal& y) {
    return x.votes > y.votes;
  });
  return out;
}

}  // namespace matching
}  // namespace is_graphs
