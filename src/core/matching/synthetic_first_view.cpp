#include "is_graphs/matching/synthetic_first_view.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <vector>

#include "is_graphs/geometry/se3.h"

namespace is_graphs {
namespace matching {
namespace {

struct Piece {
  Eigen::Vector2d a, b;
  int surface{-1};  // A-surface id, -1: clutter or the world outside
  int key{0};       // what one plane is made of (a surface, one face of a box)
};

bool InPolygon(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
  bool in = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
    if ((poly[i].y() > p.y()) != (poly[j].y() > p.y()) &&
        p.x() < (poly[j].x() - poly[i].x()) * (p.y() - poly[i].y()) / (poly[j].y() - poly[i].y()) +
                    poly[i].x())
      in = !in;
  return in;
}

double DistanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                         const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-12), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

/// The distance along the ray o + s dir to segment ab (infinity when missed).
double Hit(const Eigen::Vector2d& o, const Eigen::Vector2d& dir, const Eigen::Vector2d& a,
           const Eigen::Vector2d& b) {
  const Eigen::Vector2d e = b - a;
  const double den = dir.x() * e.y() - dir.y() * e.x();
  if (std::abs(den) < 1e-12) return std::numeric_limits<double>::infinity();
  const Eigen::Vector2d w = a - o;
  const double s = (w.x() * e.y() - w.y() * e.x()) / den;
  const double u = (w.x() * dir.y() - w.y() * dir.x()) / den;
  return s > 1e-6 && u >= 0.0 && u <= 1.0 ? s : std::numeric_limits<double>::infinity();
}

/// Segment ab less the stretch [from, to] (m along it).
std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> Cut(const Eigen::Vector2d& a,
                                                             const Eigen::Vector2d& b, double from,
                                                             double to) {
  const double len = (b - a).norm();
  const Eigen::Vector2d t = (b - a) / std::max(len, 1e-12);
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> out;
  if (from > 0.0) out.emplace_back(a, a + std::min(from, len) * t);
  if (to < len) out.emplace_back(a + std::max(to, 0.0) * t, b);
  return out;
}

}  // namespace

SyntheticSGraph MakeFirstView(const agraph::AGraph& building, const FirstViewConfig& c) {
  SyntheticSGraph out;
  out.bim_T_map = c.bim_T_map;
  if (c.room < 0 || c.room >= static_cast<int>(building.rooms.size())) return out;
  const agraph::Room& room = building.rooms[c.room];
  std::mt19937_64 rng(c.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Piece> pieces;
  std::map<int, const agraph::WallSurface*> by_id;
  for (const auto& s : building.surfaces)
    if (s.storey == room.storey) {
      pieces.push_back({s.start, s.end, s.id, s.id});
      by_id[s.id] = &s;
    }
  // The robot: a spot of the room 0.4 m from every wall (20 tries), any heading.
  Eigen::AlignedBox2d box;
  for (const auto& v : room.polygon) box.extend(v);
  Eigen::Vector2d robot;
  bool found = false;
  for (int k = 0; k < 20 && !found; ++k) {
    robot = box.min() + Eigen::Vector2d(unit(rng), unit(rng)).cwiseProduct(box.sizes());
    if (!InPolygon(room.polygon, robot)) continue;
    found = std::all_of(pieces.begin(), pieces.end(),
                        [&](const Piece& p) { return DistanceToSegment(robot, p.a, p.b) >= 0.4; });
  }
  if (!found) return out;
  const double heading = 2.0 * M_PI * unit(rng);
  // As built: surfaces near the robot moved or turned, windows in external walls.
  auto near = [&](const Piece& p) {
    return p.surface >= 0 && DistanceToSegment(robot, p.a, p.b) < 0.6 * c.max_range;
  };
  std::vector<int> candidates;
  for (size_t i = 0; i < pieces.size(); ++i)
    if (near(pieces[i])) candidates.push_back(static_cast<int>(i));
  std::shuffle(candidates.begin(), candidates.end(), rng);
  size_t next = 0;
  for (int k = 0; k < c.moved_walls && next < candidates.size(); ++k, ++next) {
    Piece& p = pieces[candidates[next]];
    const Eigen::Vector2d n = by_id[p.surface]->plane.normal.head<2>().normalized();
    const double by = (unit(rng) < 0.5 ? -1.0 : 1.0) * (0.2 + 0.15 * unit(rng));
    p.a += by * n, p.b += by * n;
    out.moved[p.surface] = by;
  }
  for (int k = 0; k < c.turned_walls && next < candidates.size(); ++k, ++next) {
    Piece& p = pieces[candidates[next]];
    const double angle = (2.0 * unit(rng) - 1.0) * 15.0 * M_PI / 180.0;
    const Eigen::Vector2d m = 0.5 * (p.a + p.b);
    const Eigen::Rotation2Dd r(angle);
    p.a = m + r * (p.a - m), p.b = m + r * (p.b - m);
    out.turned[p.surface] = angle;
  }
  int key = 1000000;
  for (int k = 0; k < c.windows; ++k) {
    // An external wall near the robot, both faces cut at one stretch; a façade beyond.
    std::vector<const agraph::Wall*> external;
    for (const auto& w : building.walls)
      if (w.external && w.storey == room.storey && w.length > 2.0 &&
          (w.center.head<2>() - robot).norm() < 0.6 * c.max_range)
        external.push_back(&w);
    if (external.empty()) break;
    const agraph::Wall& w =
        *external[std::uniform_int_distribution<size_t>(0, external.size() - 1)(rng)];
    const double width = 1.2 + 1.3 * unit(rng);
    std::vector<Piece> kept;
    Eigen::Vector2d centre = w.center.head<2>(), outward = Eigen::Vector2d::Zero();
    for (const Piece& p : pieces) {
      if (p.surface != w.surface_a && p.surface != w.surface_b) {
        kept.push_back(p);
        continue;
      }
      const double len = (p.b - p.a).norm();
      const Eigen::Vector2d t = (p.b - p.a) / std::max(len, 1e-12);
      const double mid = (centre - p.a).dot(t);
      for (const auto& [a, b] : Cut(p.a, p.b, mid - 0.5 * width, mid + 0.5 * width))
        kept.push_back({a, b, p.surface, p.key});
      if (by_id[p.surface]->rooms.empty()) outward = by_id[p.surface]->plane.normal.head<2>();
    }
    pieces.swap(kept);
    if (outward.norm() < 0.5) continue;
    const double far = 10.0 + 20.0 * unit(rng);
    const Eigen::Vector2d f = centre + far * outward.normalized();
    const Eigen::Vector2d along(-outward.y(), outward.x());
    pieces.push_back({f - 6.0 * along.normalized(), f + 6.0 * along.normalized(), -1, key++});
  }
  // Clutter: boxes in the room, clear of the robot by 0.5 m.
  for (int k = 0; k < c.clutter; ++k) {
    const Eigen::Vector2d centre =
        box.min() + Eigen::Vector2d(unit(rng), unit(rng)).cwiseProduct(box.sizes());
    const double sx = 0.3 + 0.9 * unit(rng), sy = 0.3 + 0.9 * unit(rng);
    if (!InPolygon(room.polygon, centre) ||
        (centre - robot).norm() < 0.5 + 0.5 * std::hypot(sx, sy))
      continue;
    const Eigen::Rotation2Dd r(M_PI * unit(rng));
    const Eigen::Vector2d v[4] = {
        centre + r * Eigen::Vector2d(-sx, -sy) * 0.5, centre + r * Eigen::Vector2d(sx, -sy) * 0.5,
        centre + r * Eigen::Vector2d(sx, sy) * 0.5, centre + r * Eigen::Vector2d(-sx, sy) * 0.5};
    for (int e = 0; e < 4; ++e) pieces.push_back({v[e], v[(e + 1) % 4], -1, key++});
  }
  // The scan: each ray's nearest hit.
  const Eigen::Isometry3d map_T_bim = c.bim_T_map.inverse();
  const Eigen::Rotation2Dd to_base(-heading);
  std::normal_distribution<double> noise(0.0, c.range_noise);
  struct Hits {
    Eigen::Vector2d lo, hi;
    double from{1e18}, to{-1e18};
    int count{0};
  };
  std::map<int, Hits> hits;  // by piece key
  std::map<int, const Piece*> piece_of;
  sgraph::Keyframe k;
  k.id = 0;
  const double z = room.floor_z + 0.525;  // base_link above the floor
  Eigen::Isometry3d bim_T_base = Eigen::Isometry3d::Identity();
  bim_T_base.linear() = Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  bim_T_base.translation() = Eigen::Vector3d(robot.x(), robot.y(), z);
  k.pose = map_T_bim * bim_T_base;
  k.odom_pose = k.pose;
  for (int i = 0; i < c.rays; ++i) {
    const double a = 2.0 * M_PI * i / c.rays;
    const Eigen::Vector2d dir(std::cos(a), std::sin(a));
    double best = c.max_range;
    const Piece* hit = nullptr;
    for (const Piece& p : pieces) {
      const double s = Hit(robot, dir, p.a, p.b);
      if (s < best) best = s, hit = &p;
    }
    if (!hit) continue;
    const double range = best + noise(rng);
    const Eigen::Vector2d q = robot + range * dir;
    const Eigen::Vector2d local = to_base * (q - robot);
    k.slice.emplace_back(static_cast<float>(local.x()), static_cast<float>(local.y()), 1.0f);
    Hits& h = hits[hit->key];
    piece_of[hit->key] = hit;
    const Eigen::Vector2d t = (hit->b - hit->a).normalized();
    const double along = (q - hit->a).dot(t);
    if (along < h.from) h.from = along, h.lo = hit->a + along * t;
    if (along > h.to) h.to = along, h.hi = hit->a + along * t;
    ++h.count;
  }
  out.graph.keyframes.push_back(k);
  // A plane per piece hit along min_plane_length (3 or more hits), normal towards the robot.
  std::normal_distribution<double> tilt(0.0, c.plane_noise_deg * M_PI / 180.0);
  for (const auto& [piece_key, h] : hits) {
    if (h.count < 3 || h.to - h.from < c.min_plane_length) continue;
    const Piece& p = *piece_of.at(piece_key);
    const Eigen::Vector2d t = (p.b - p.a).normalized();
    Eigen::Vector2d n(-t.y(), t.x());
    if (n.dot(robot - p.a) < 0.0) n = -n;
    n = Eigen::Rotation2Dd(tilt(rng)) * n;
    const Eigen::Vector2d mid = 0.5 * (h.lo + h.hi);
    sgraph::Plane plane;
    plane.id = static_cast<int>(out.graph.planes.size());
    const Eigen::Vector3d n_b(n.x(), n.y(), 0.0);
    plane.plane = geometry::Plane::FromPointNormal(Eigen::Vector3d(mid.x(), mid.y(), z), n_b)
                      .Transformed(map_T_bim);
    plane.orientation = geometry::ClassifyOrientation(plane.plane.normal);
    plane.start = (map_T_bim * Eigen::Vector3d(h.lo.x(), h.lo.y(), z)).head<2>();
    plane.end = (map_T_bim * Eigen::Vector3d(h.hi.x(), h.hi.y(), z)).head<2>();
    plane.z_min = z - 0.5;
    plane.z_max = z + 1.8;
    plane.num_points = 20 * h.count;
    if (p.surface >= 0) out.plane_truth[plane.id] = p.surface;
    out.graph.observations.push_back(
        {k.id, plane.id, plane.plane.Transformed(k.pose.inverse()), Eigen::Matrix3d::Identity()});
    out.graph.planes.push_back(plane);
  }
  out.graph.revision = 1;
  return out;
}

}  // namespace matching
}  // namespace is_graphs
