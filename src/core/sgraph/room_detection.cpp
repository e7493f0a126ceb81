#include "is_graphs/sgraph/room_detection.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace is_graphs {
namespace sgraph {

bool SameLine(const Wall2D& a, const Wall2D& b) {
  return a.normal.dot(b.normal) > std::cos(3.0 * M_PI / 180.0) && std::abs(a.d - b.d) < 0.1;
}

const Wall2D* FindWall(const std::vector<Wall2D>& walls, int id) {
  for (const Wall2D& w : walls)
    if (w.id == id) return &w;
  return nullptr;
}

bool LeftOutLieBehind(const std::vector<Wall2D>& walls, const std::vector<int>& all,
                      const std::vector<int>& kept) {
  constexpr double kBehind = 0.1;  // m
  for (int id : all) {
    if (std::count(kept.begin(), kept.end(), id) > 0) continue;
    const Wall2D* w = FindWall(walls, id);
    if (!w) return false;
    const bool behind = std::any_of(kept.begin(), kept.end(), [&](int k) {
      const Wall2D* c = FindWall(walls, k);
      return c && c->normal.dot(w->start) - c->d < -kBehind &&
             c->normal.dot(w->end) - c->d < -kBehind;
    });
    if (!behind) return false;
  }
  return true;
}

namespace {

constexpr double kRectangleSlack = 0.2;  // m: a hit this far outside a rectangle is on it
constexpr double kCornerSlack = 0.3;     // m: a wall's seen extent, grown by this (corners)
constexpr double kMinDividing = 0.5;     // m: the least of a wall seen across a rectangle
constexpr double kMinSetback = 0.1;      // m: behind a wall by this (SameLine's offset) ...
constexpr double kMaxSetback = 0.6;      // m: ... to this (a thick exterior wall): in its depth

Eigen::Vector2d Along(const Wall2D& w) { return Eigen::Vector2d(-w.normal.y(), w.normal.x()); }

/// The interval [lo, hi] of `w`'s seen extent along `along`.
std::pair<double, double> SeenExtent(const Wall2D& w, const Eigen::Vector2d& along) {
  const double a = along.dot(w.start), b = along.dot(w.end);
  return {std::min(a, b), std::max(a, b)};
}

/// Where the lines of walls p and q cross.
Eigen::Vector2d Corner(const Wall2D& p, const Wall2D& q) {
  Eigen::Matrix2d m;
  m << p.normal.transpose(), q.normal.transpose();
  return m.fullPivLu().solve(Eigen::Vector2d(p.d, q.d));
}

/// The widest stretch of [s0, s1] along `line` that no wall on that line covers, each wall's
/// seen extent grown by `slack` at both ends; the length covered in `covered_length`. With
/// `openings`, what is seen through an opening of `line` (SeenThroughOpening) covers it too.
double LargestGap(const std::vector<Wall2D>& walls, const Wall2D& line, double s0, double s1,
                  double slack, double* covered_length = nullptr, bool openings = false) {
  if (s0 > s1) std::swap(s0, s1);
  const Eigen::Vector2d along = Along(line);
  std::vector<std::pair<double, double>> covered;
  for (const Wall2D& other : walls) {
    if (!SameLine(other, line) && !(openings && SeenThroughOpening(line, other))) continue;
    const auto [lo, hi] = SeenExtent(other, along);
    covered.emplace_back(lo - slack, hi + slack);
  }
  std::sort(covered.begin(), covered.end());
  double largest = 0.0, reached = s0, length = 0.0;
  for (const auto& [lo, hi] : covered) {
    if (lo > reached) largest = std::max(largest, std::min(lo, s1) - reached);
    length += std::max(0.0, std::min(hi, s1) - std::max(lo, reached));
    reached = std::max(reached, hi);
    if (reached >= s1) break;
  }
  if (covered_length) *covered_length = length;
  return std::max(largest, s1 - reached);
}

/// The widest stretch of the rectangle's sides (walls {a0, a1} and {b0, b1} opposed) that no
/// wall on the side's line covers: a doorway is narrow, the rest of an L-shaped room is not.
double LargestOpening(const std::vector<Wall2D>& walls, const int four[4]) {
  double largest = 0.0;
  for (int side = 0; side < 4; ++side) {
    const Wall2D& w = walls[four[side]];
    const int* across = side < 2 ? four + 2 : four;  // the other pair bounds this side
    const Eigen::Vector2d along = Along(w);
    largest = std::max(
        largest, LargestGap(walls, w, along.dot(Corner(w, walls[across[0]])),
                            along.dot(Corner(w, walls[across[1]])), kCornerSlack, nullptr, true));
  }
  return largest;
}

/// Whether a mapped wall parallel to one pair of the rectangle runs across its inside (seen
/// there over kMinDividing at least), leaving no more than `max_opening` open (a doorway): the
/// rectangle is two spaces (a corridor and the room seen through its door), not a room. A partition
/// that leaves a wide passage, or clutter, does not divide it. Seen extents only (no corner slack).
bool DividedByWall(const std::vector<Wall2D>& walls, const int four[4], double max_opening) {
  for (const Wall2D& w : walls) {
    if (std::any_of(four, four + 4, [&](int f) { return SameLine(w, walls[f]); })) continue;
    int pair = -1;
    for (int k = 0; k < 2; ++k)
      if (std::abs(w.normal.dot(walls[four[2 * k]].normal)) > std::cos(0.2)) pair = k;
    if (pair < 0) continue;
    const Eigen::Vector2d mid = 0.5 * (w.start + w.end);
    const bool inside = std::all_of(four + 2 * pair, four + 2 * pair + 2, [&](int f) {
      return walls[f].normal.dot(mid) - walls[f].d > kRectangleSlack;
    });
    if (!inside) continue;
    const int* across = four + 2 * (1 - pair);
    const Eigen::Vector2d along = Along(w);
    double covered = 0.0;
    const double gap = LargestGap(walls, w, along.dot(Corner(w, walls[across[0]])),
                                  along.dot(Corner(w, walls[across[1]])), 0.0, &covered);
    if (covered >= kMinDividing && gap <= max_opening) return true;
  }
  return false;
}

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

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Whether the segments [p0, p1] and [q0, q1] cross (ends within `tol` count).
bool SegmentsCross(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Eigen::Vector2d& q0,
                   const Eigen::Vector2d& q1, double tol) {
  const Eigen::Vector2d r = p1 - p0, s = q1 - q0;
  const double denom = Cross(r, s);
  if (std::abs(denom) < 1e-12) return false;  // parallel
  const double t = Cross(q0 - p0, s) / denom, u = Cross(q0 - p0, r) / denom;
  const double tt = tol / std::max(r.norm(), 1e-9), tu = tol / std::max(s.norm(), 1e-9);
  return t >= -tt && t <= 1.0 + tt && u >= -tu && u <= 1.0 + tu;
}

}  // namespace

bool SeenThroughOpening(const Wall2D& front, const Wall2D& behind) {
  if (front.normal.dot(behind.normal) <= std::cos(3.0 * M_PI / 180.0)) return false;
  const double setback = front.d - behind.d;  // normals point into the room
  if (setback < kMinSetback || setback > kMaxSetback) return false;
  const Eigen::Vector2d along = Along(front);
  const auto [f0, f1] = SeenExtent(front, along);
  const auto [b0, b1] = SeenExtent(behind, along);
  return f0 < b0 - kCornerSlack || f1 > b1 + kCornerSlack;
}

bool SameSpace(const std::vector<Wall2D>& walls, const std::vector<int>& a_walls,
               const Eigen::Vector2d& a_center, const std::vector<int>& b_walls,
               const Eigen::Vector2d& b_center) {
  constexpr double kSlack = 0.3;  // m: a centre may sit this far behind a wall (as InsideWalls)
  auto between = [&](const Wall2D& w, const Eigen::Vector2d& p) {
    return w.normal.dot(p) - w.d > -kSlack;
  };
  std::vector<const Wall2D*> shared;
  for (int id : a_walls)
    if (std::count(b_walls.begin(), b_walls.end(), id) > 0)
      if (const Wall2D* w = FindWall(walls, id)) shared.push_back(w);
  bool pair = false;
  for (size_t i = 0; i < shared.size() && !pair; ++i)
    for (size_t j = i + 1; j < shared.size() && !pair; ++j)
      pair = shared[i]->normal.dot(shared[j]->normal) < -std::cos(0.2) &&
             between(*shared[i], a_center) && between(*shared[j], a_center) &&
             between(*shared[i], b_center) && between(*shared[j], b_center);
  if (!pair) return false;
  for (const Wall2D& w : walls)  // a wall seen between the centres separates two rooms
    if (SegmentsCross(a_center, b_center, w.start, w.end, 0.05)) return false;
  return true;
}

bool InOpening(const std::vector<Wall2D>& walls, const Eigen::Vector2d& position,
               const FrontendConfig& config) {
  for (const Wall2D& w : walls) {
    if (std::abs(w.normal.dot(position) - w.d) > config.room_opening_band) continue;
    const Eigen::Vector2d along = Along(w);
    const auto [lo, hi] = SeenExtent(w, along);
    const double s = along.dot(position);
    if (s >= lo - config.room_gap_margin && s <= hi + config.room_gap_margin) return true;
  }
  return false;
}

bool InFan(const RayFan& fan, const Eigen::Vector2d& position, const Eigen::Vector2d& point,
           double margin) {
  const int n = static_cast<int>(fan.directions.size());
  if (n == 0) return false;
  const Eigen::Vector2d v = point - position;
  double a = std::atan2(v.y(), v.x());
  if (a < 0.0) a += 2.0 * M_PI;
  const int k = static_cast<int>(std::lround(a / (2.0 * M_PI) * n)) % n;
  return v.norm() < fan.range[k] - margin;
}

RayFan CastRays(const std::vector<Wall2D>& walls, const Eigen::Vector2d& position,
                const FrontendConfig& config) {
  RayFan fan;
  const int n = config.room_rays;
  fan.directions.resize(n);
  fan.hit.assign(n, -1);
  fan.range.assign(n, std::numeric_limits<double>::infinity());
  fan.on_extent.assign(n, 0);
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * M_PI * k / n;
    fan.directions[k] = Eigen::Vector2d(std::cos(a), std::sin(a));
  }
  // Margins bridge doorways and unseen corners but never hide a wall seen behind them (the
  // far wall of a corridor behind the margin of an office's side wall): a hit on a margin
  // counts only for a ray that hits no wall on its seen extent.
  std::vector<double> bridge_range(n, std::numeric_limits<double>::infinity());
  std::vector<int> bridge_hit(n, -1);
  for (size_t w = 0; w < walls.size(); ++w) {
    const Wall2D& wall = walls[w];
    const double front = wall.normal.dot(position) - wall.d;
    if (front < 0.1 || front > config.room_max_range) continue;  // faces away, or too far
    const Eigen::Vector2d along = Along(wall);
    const auto [lo, hi] = SeenExtent(wall, along);
    for (int k = 0; k < n; ++k) {
      const double cosine = wall.normal.dot(fan.directions[k]);
      if (cosine > -1e-6) continue;  // parallel or away
      const double t = front / -cosine;
      if (t > config.room_max_range) continue;
      const double s = along.dot(position + t * fan.directions[k]);
      const bool seen = s >= lo - kCornerSlack && s <= hi + kCornerSlack;
      if (seen && t < fan.range[k]) {
        fan.range[k] = t;
        fan.hit[k] = static_cast<int>(w);
        fan.on_extent[k] = s >= lo && s <= hi;
      } else if (!seen && s >= lo - config.room_gap_margin && s <= hi + config.room_gap_margin &&
                 t < bridge_range[k]) {
        bridge_range[k] = t;
        bridge_hit[k] = static_cast<int>(w);
      }
    }
  }
  for (int k = 0; k < n; ++k)
    if (fan.hit[k] < 0 && bridge_hit[k] >= 0)
      fan.hit[k] = bridge_hit[k], fan.range[k] = bridge_range[k];
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
  std::vector<int> seen(walls.size(), 0);  // hits on the seen extent itself
  for (int k = 0; k < n; ++k)
    if (fan.hit[k] >= 0 && k < static_cast<int>(fan.on_extent.size()) && fan.on_extent[k])
      ++seen[fan.hit[k]];
  auto bounds = [&](int w) { return count[w] >= significant && seen[w] >= significant; };
  int gaps = 0;
  for (int h : fan.hit)
    if (h < 0 || !bounds(h)) ++gaps;
  if (gaps > n / 20) return std::nullopt;  // open: some direction escapes
  RoomCandidate room;
  std::vector<int> members;
  for (size_t w = 0; w < walls.size(); ++w)
    if (bounds(static_cast<int>(w))) members.push_back(static_cast<int>(w));
  if (members.size() < 3) return std::nullopt;
  // The visibility polygon (hits of the counted rays) gives area and centroid.
  std::vector<Eigen::Vector2d> polygon;
  for (int k = 0; k < n; ++k)
    if (fan.hit[k] >= 0 && bounds(fan.hit[k]))
      polygon.push_back(position + fan.range[k] * fan.directions[k]);
  double area = 0.0;
  room.center = PolygonCentroid(polygon, &area);
  if (area < config.room_min_width * config.room_min_width) return std::nullopt;
  room.area = area;
  // The paper's four-wall room: two opposed pairs of walls that take (almost) every ray; other
  // members then are walls seen through a doorway and are left out.
  struct Rectangle {
    int walls[4];
    int rays{0};
    Eigen::Vector2d center;
  };
  std::optional<Rectangle> best;
  std::vector<std::pair<int, int>> opposed;
  for (size_t i = 0; i < members.size(); ++i)
    for (size_t j = i + 1; j < members.size(); ++j)
      if (walls[members[i]].normal.dot(walls[members[j]].normal) < -std::cos(0.2))
        opposed.emplace_back(members[i], members[j]);
  for (size_t p = 0; p < opposed.size(); ++p) {
    for (size_t q = p + 1; q < opposed.size(); ++q) {
      const auto [a0, a1] = opposed[p];
      const auto [b0, b1] = opposed[q];
      if (a0 == b0 || a0 == b1 || a1 == b0 || a1 == b1) continue;
      const int four[4] = {a0, a1, b0, b1};
      // Mid-lines: (n_a − n_b)·ρ = d_a − d_b for each pair.
      Eigen::Matrix2d m;
      Eigen::Vector2d rhs;
      bool widths_ok = true;
      for (int k = 0; k < 2; ++k) {
        const Wall2D& wa = walls[four[2 * k]];
        const Wall2D& wb = walls[four[2 * k + 1]];
        m.row(k) = (wa.normal - wb.normal).transpose();
        rhs(k) = wa.d - wb.d;
        const double width = (wa.normal.dot(position) - wa.d) + (wb.normal.dot(position) - wb.d);
        widths_ok = widths_ok && width >= config.room_min_width && width <= config.room_max_width;
      }
      if (!widths_ok || std::abs(m.determinant()) <= 0.3) continue;
      // The rays that end on one of the four walls within the rectangle they bound (a wall
      // seen through a doorway lies outside it).
      // Each of the four must take rays of its own: a wall that only bounds the rectangle
      // somewhere unseen (an office's side wall beyond a corridor's doorway) does not.
      int rays = 0, per_wall[4] = {0, 0, 0, 0};
      for (int k = 0; k < n; ++k) {
        const int h = fan.hit[k];
        if (h < 0) continue;
        int side = static_cast<int>(
            std::find_if(four, four + 4, [&](int w) { return SameLine(walls[h], walls[w]); }) -
            four);
        // A hit in the depth of a side (a pane, a reveal seen through its opening) is that
        // side's: the room is bounded by the wall's face, not by what is set in it.
        const bool through = side == 4 && [&] {
          side = static_cast<int>(
              std::find_if(four, four + 4,
                           [&](int w) { return SeenThroughOpening(walls[w], walls[h]); }) -
              four);
          return side < 4;
        }();
        if (side == 4) continue;
        const Eigen::Vector2d hit = position + fan.range[k] * fan.directions[k];
        bool inside = true;
        for (int s = 0; s < 4; ++s)
          inside = inside && ((through && s == side) ||
                              walls[four[s]].normal.dot(hit) - walls[four[s]].d > -kRectangleSlack);
        if (!inside) continue;
        ++rays;
        ++per_wall[side];
      }
      if (*std::min_element(per_wall, per_wall + 4) < significant) continue;
      if (LargestOpening(walls, four) > config.room_max_opening) continue;
      if (DividedByWall(walls, four, config.room_max_opening)) continue;
      if (!best || rays > best->rays)
        best = Rectangle{{a0, a1, b0, b1}, rays, m.fullPivLu().solve(rhs)};
    }
  }
  if (best && best->rays >= config.room_rectangle_share * n) {
    room.center = best->center;
    room.rectangular = true;
    room.share = static_cast<double>(best->rays) / n;
    members.assign(best->walls, best->walls + 4);
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
