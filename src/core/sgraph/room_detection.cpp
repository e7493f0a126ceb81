#include "is_graphs/sgraph/room_detection.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace is_graphs {
namespace sgraph {
namespace {

Eigen::Vector2d Along(const Wall2D& w) { return Eigen::Vector2d(-w.normal.y(), w.normal.x()); }

// Area centroid of a closed polygon (shoelace); the vertex mean for a degenerate one.
Eigen::Vector2d PolygonCentroid(const std::vector<Eigen::Vector2d>& polygon, double* area) {
  double a = 0.0;
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& p = polygon[i];
    const Eigen::Vector2d& q = polygon[(i + 1) % polygon.size()];
    const double cross = p.x() * q.y() - q.x() * p.y();
    a += cross;
    c += (p + q) * cross;
  }
  a *= 0.5;
  if (area) *area = std::abs(a);
  if (std::abs(a) < 1e-9) {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const auto& p : polygon) mean += p;
    return polygon.empty() ? mean : Eigen::Vector2d(mean / polygon.size());
  }
  return c / (6.0 * a);
}

}  // namespace

RayFan CastRays(const std::vector<Wall2D>& walls, const Eigen::Vector2d& position,
                const FrontendConfig& config) {
  RayFan fan;
  const int n = config.room_rays;
  fan.directions.resize(n);
  fan.hit.assign(n, -1);
  fan.range.assign(n, std::numeric_limits<double>::infinity());
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * M_PI * k / n;
    fan.directions[k] = Eigen::Vector2d(std::cos(a), std::sin(a));
  }
  for (size_t w = 0; w < walls.size(); ++w) {
    const Wall2D& wall = walls[w];
    const double front = wall.normal.dot(position) - wall.d;
    if (front < 0.1 || front > config.room_max_range) continue;  // faces away, or too far
    const Eigen::Vector2d along = Along(wall);
    double lo = along.dot(wall.start), hi = along.dot(wall.end);
    if (lo > hi) std::swap(lo, hi);
    lo -= config.room_gap_margin;
    hi += config.room_gap_margin;
    for (int k = 0; k < n; ++k) {
      const double cosine = wall.normal.dot(fan.directions[k]);
      if (cosine > -1e-6) continue;  // parallel or away
      const double t = front / -cosine;
      if (t > config.room_max_range || t >= fan.range[k]) continue;
      const double s = along.dot(position + t * fan.directions[k]);
      if (s < lo || s > hi) continue;
      fan.range[k] = t;
      fan.hit[k] = static_cast<int>(w);
    }
  }
  return fan;
}

std::vector<int> CountHits(const RayFan& fan, size_t num_walls) {
  std::vector<int> count(num_walls, 0);
  for (int h : fan.hit)
    if (h >= 0) ++count[h];
  return count;
}

std::optional<RoomCandidate> DetectRoom(const std::vector<Wall2D>& walls,
                                        const Eigen::Vector2d& position, const RayFan& fan,
                                        const FrontendConfig& config) {
  const int n = static_cast<int>(fan.hit.size());
  if (n == 0) return std::nullopt;
  const std::vector<int> count = CountHits(fan, walls.size());
  const int significant = std::max(3, n / 50);
  int gaps = 0;
  for (int h : fan.hit)
    if (h < 0 || count[h] < significant) ++gaps;
  if (gaps > n / 20) return std::nullopt;  // open: some direction escapes
  RoomCandidate room;
  std::vector<int> members;
  for (size_t w = 0; w < walls.size(); ++w)
    if (count[w] >= significant) members.push_back(static_cast<int>(w));
  if (members.size() < 3) return std::nullopt;
  // The visibility polygon (hits of the counted rays) gives area and centroid.
  std::vector<Eigen::Vector2d> polygon;
  for (int k = 0; k < n; ++k)
    if (fan.hit[k] >= 0 && count[fan.hit[k]] >= significant)
      polygon.push_back(position + fan.range[k] * fan.directions[k]);
  double area = 0.0;
  room.center = PolygonCentroid(polygon, &area);
  if (area < config.room_min_width * config.room_min_width) return std::nullopt;
  // The paper's four-wall room: exactly two opposed pairs.
  if (members.size() == 4) {
    std::vector<std::pair<int, int>> pairs;
    std::vector<bool> paired(4, false);
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        if (!paired[i] && !paired[j] &&
            walls[members[i]].normal.dot(walls[members[j]].normal) < -std::cos(0.2)) {
          pairs.emplace_back(members[i], members[j]);
          paired[i] = paired[j] = true;
        }
    if (pairs.size() == 2) {
      // Mid-lines: (n_a − n_b)·ρ = d_a − d_b for each pair.
      Eigen::Matrix2d a;
      Eigen::Vector2d b;
      bool widths_ok = true;
      for (int p = 0; p < 2; ++p) {
        const Wall2D& wa = walls[pairs[p].first];
        const Wall2D& wb = walls[pairs[p].second];
        a.row(p) = (wa.normal - wb.normal).transpose();
        b(p) = wa.d - wb.d;
        const double width = (wa.normal.dot(position) - wa.d) + (wb.normal.dot(position) - wb.d);
        widths_ok = widths_ok && width >= config.room_min_width && width <= config.room_max_width;
      }
      if (widths_ok && std::abs(a.determinant()) > 0.3) {
        room.center = a.fullPivLu().solve(b);
        room.rectangular = true;
      }
    }
  }
  room.type = RoomType::kRoom;
  for (int m : members) {
    room.walls.push_back(walls[m].id);
    room.distances.push_back(walls[m].normal.dot(room.center) - walls[m].d);
  }
  return room;
}

}  // namespace sgraph
}  // namespace is_graphs
