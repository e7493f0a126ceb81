// ClassifyDoorways: each IFC door or opening present or closed (issue 21; docs/deviations.md).
#include "is_graphs/merging/doorway_status.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "wall_sight_lines.h"

namespace is_graphs {
namespace merging {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

/// An A-wall in B: its mid-line, the unit normal of its first surface, its gaps (doorways).
struct WallLine {
  Eigen::Vector2d start{Eigen::Vector2d::Zero()}, end{Eigen::Vector2d::Zero()};
  Eigen::Vector2d normal{Eigen::Vector2d::UnitX()};
  double half_thickness{0.0};
  std::vector<detail::Gap> gaps;
};

/// The walls of the storey at height z_robot (as ClassifyWalls selects them), by A-Graph id.
std::map<int, WallLine> WallLines(const agraph::AGraph& building, double z_robot,
                                  double door_margin) {
  std::map<int, const agraph::WallSurface*> surfaces;
  for (const auto& s : building.surfaces) surfaces[s.id] = &s;
  std::map<int, WallLine> out;
  for (const auto& w : building.walls) {
    const int id = surfaces.count(w.surface_a) ? w.surface_a : w.surface_b;
    if (!surfaces.count(id)) continue;
    const agraph::WallSurface& first = *surfaces[id];
    if (z_robot < first.z_min - 0.5 || z_robot > first.z_max) continue;
    WallLine l;
    l.normal = first.plane.normal.head<2>().normalized();
    l.half_thickness = 0.5 * w.thickness;
    l.start = first.start - l.half_thickness * l.normal;  // the face's normal points out of it
    l.end = first.end - l.half_thickness * l.normal;
    out[w.id] = l;
  }
  for (const auto& d : building.doorways)
    if (d.InWall() && out.count(d.wall))
      out[d.wall].gaps.push_back({d.position.head<2>(), 0.5 * d.width + door_margin});
  return out;
}

/// The sight line v-q passes through no A-wall but `own` (outside their doorways).
bool Clear(const Eigen::Vector2d& v, const Eigen::Vector2d& q, int own,
           const std::map<int, WallLine>& walls) {
  for (const auto& [id, w] : walls)
    if (id != own && detail::Through(v, q, w.start, w.end, w.gaps)) return false;
  return true;
}

/// How much of the opening (centre c, direction t, half width h) S-plane p spans, m.
double Cover(const detail::PlaneInB& p, const Eigen::Vector2d& c, const Eigen::Vector2d& t,
             double h) {
  const double u1 = (p.start - c).dot(t), u2 = (p.end - c).dot(t);
  return std::max(0.0, std::min(h, std::max(u1, u2)) - std::max(-h, std::min(u1, u2)));
}

/// The first S-plane (index; -1 none) the sight line from v through the opening's centre c meets
/// beyond the wall (past `beyond` m from v), facing v, within its extent, before any other A-wall
/// but `own`: what v would have seen through the opening, had it been open.
int FirstPlaneBeyond(const Eigen::Vector2d& v, const Eigen::Vector2d& c, double beyond, int own,
                     const std::vector<detail::PlaneInB>& planes,
                     const std::map<int, WallLine>& walls) {
  const Eigen::Vector2d dir = (c - v).normalized();
  int best = -1;
  double nearest = 1e9;
  for (size_t i = 0; i < planes.size(); ++i) {
    const detail::PlaneInB& p = planes[i];
    const double cos = p.normal.dot(dir);
    if (cos > -0.2) continue;  // seen edge-on or from behind
    const double s = (p.d - p.normal.dot(v)) / cos;
    if (s <= beyond || s >= nearest) continue;
    const Eigen::Vector2d x = v + s * dir;
    const double length = p.Length();
    const double u = length > 0.0 ? (x - p.start).dot(p.end - p.start) / length : -1.0;
    if (u < -0.1 || u > length + 0.1) continue;
    best = static_cast<int>(i), nearest = s;
  }
  return best >= 0 && Clear(v, v + (nearest - 0.05) * dir, own, walls) ? best : -1;
}

}  // namespace

const char* ToString(DoorwayStatus status) {
  switch (status) {
    case DoorwayStatus::kPresent:
      return "PRESENT";
    case DoorwayStatus::kClosed:
      return "CLOSED";
    case DoorwayStatus::kNotSeen:
      return "NOT_SEEN";
  }
  return "?";
}

std::string DoorwayDeviationConfig::Validate() const {
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  auto non_negative = [](double v) { return std::isfinite(v) && v >= 0.0; };
  if (!positive(default_width)) return "default_width: must be > 0 m";
  if (!non_negative(walk_margin)) return "walk_margin: must be >= 0 m";
  if (!positive(view_distance)) return "view_distance: must be > 0 m";
  if (present_min_rays < 1) return "present_min_rays: must be >= 1";
  if (!positive(closed_min_cover) || closed_min_cover > 1.0)
    return "closed_min_cover: must be in (0, 1]";
  if (!non_negative(closed_max_offset)) return "closed_max_offset: must be >= 0 m";
  if (!non_negative(closed_min_height)) return "closed_min_height: must be >= 0 m";
  if (closed_min_views < 1) return "closed_min_views: must be >= 1";
  return "";
}

std::vector<DoorwayDeviation> ClassifyDoorways(const agraph::AGraph& building,
                                               const sgraph::SGraph& graph,
                                               const Eigen::Isometry3d& bim_T_map,
                                               const WallDeviationConfig& walls_config,
                                               const DoorwayDeviationConfig& config) {
  const Eigen::Isometry3d b_T_m = ConsensusBimTMap(building, graph, bim_T_map, walls_config);
  const std::map<int, WallLine> walls =
      WallLines(building, detail::RobotHeight(graph, b_T_m), walls_config.door_margin);
  const std::vector<detail::PlaneInB> planes = detail::PlanesInB(graph, b_T_m);
  const std::vector<detail::PathStep> path = detail::WalkedPathInB(graph, b_T_m);
  std::map<int, int> plane_index;  // S-plane id -> index into planes
  for (size_t i = 0; i < planes.size(); ++i) plane_index[planes[i].id] = static_cast<int>(i);
  std::map<int, Eigen::Vector2d> keyframes;  // id -> position in B
  for (const auto& k : graph.keyframes) keyframes[k.id] = (b_T_m * k.pose.translation()).head<2>();
  std::map<int, std::vector<int>> observed;  // keyframe id -> plane indices
  for (const auto& o : graph.observations)
    if (plane_index.count(o.plane) && keyframes.count(o.keyframe))
      observed[o.keyframe].push_back(plane_index[o.plane]);
  const double parallel = std::cos(walls_config.max_angle_deg * kDegToRad);

  std::vector<DoorwayDeviation> out;
  for (const auto& d : building.doorways) {
    if (!d.InWall() || !walls.count(d.wall)) continue;  // virtual, or not on this storey
    const WallLine& wall = walls.at(d.wall);
    DoorwayDeviation r;
    r.doorway_id = d.id, r.guid = d.guid, r.name = d.name, r.kind = d.kind, r.wall_id = d.wall;
    r.position = d.position.head<2>();
    r.width = d.width > 0.0 ? d.width : config.default_width;
    const Eigen::Vector2d n = wall.normal, t = (wall.end - wall.start).normalized();
    const Eigen::Vector2d c = r.position - n.dot(r.position - wall.start) * n;  // on the mid-line
    const double h = 0.5 * r.width;
    const Eigen::Vector2d s = c - h * t, e = c + h * t;  // the opening (Through keeps 0.1 m off)
    // Walked through: the S-Graph's doorways and the keyframe steps across the opening.
    for (const auto& sd : graph.doorways) {
      const Eigen::Vector2d at = (b_T_m * sd.position).head<2>();
      if (std::abs((at - c).dot(t)) <= h + config.walk_margin &&
          std::abs((at - c).dot(n)) <= wall.half_thickness + config.walk_margin)
        r.s_doorways.push_back(sd.id);
    }
    r.walked_through = static_cast<int>(r.s_doorways.size());
    for (const auto& [a, b] : path) r.walked_through += detail::Through(a, b, s, e, {});
    // Seen through, or seen covered, from the keyframes near it.
    std::set<int> covering;
    for (const auto& [k, v] : keyframes) {
      if ((v - c).norm() > config.view_distance || !observed.count(k)) continue;
      int rays = 0;
      std::vector<int> covers;
      for (int i : observed.at(k)) {
        const detail::PlaneInB& p = planes[i];
        const double off = std::abs(p.normal.dot(c) - p.d);
        const bool in_wall = std::abs(p.normal.dot(n)) >= parallel &&
                             off <= wall.half_thickness + config.closed_max_offset;
        if (in_wall) {  // the wall's face, a door leaf or a fill: does it span the opening?
          if (p.height >= config.closed_min_height && p.normal.dot(v - c) > 0.0 &&
              Cover(p, c, t, h) >= config.closed_min_cover * r.width)
            covers.push_back(p.id);
          continue;
        }
        const int samples = std::clamp(static_cast<int>(p.Length() / 0.3), 1, 16);
        for (int j = 0; j < samples; ++j) {
          const Eigen::Vector2d q =
              p.start + (j + 0.5) / samples * (p.end - p.start) + 0.2 * p.normal;
          rays += detail::Through(v, q, s, e, {}) && Clear(v, q, d.wall, walls);
        }
      }
      r.rays_through += rays;
      const Eigen::Vector2d to = c - v;
      const bool facing = std::abs(n.dot(to)) >= 0.3 && std::abs(n.dot(to)) >= 0.5 * to.norm();
      if (rays > 0 || !facing || covers.empty()) continue;
      // Blocked: what lies beyond (past the wall and what may stand in it) was mapped, seen from
      // elsewhere, and v did not see it.
      const double past =
          (wall.half_thickness + config.closed_max_offset) * to.norm() / std::abs(n.dot(to));
      const int beyond = FirstPlaneBeyond(v, c, to.norm() + past, d.wall, planes, walls);
      const auto& seen = observed.at(k);
      if (beyond >= 0 && std::find(seen.begin(), seen.end(), beyond) == seen.end()) {
        ++r.blocked_views;
        covering.insert(covers.begin(), covers.end());
      }
    }
    if (r.walked_through > 0 || r.rays_through >= config.present_min_rays) {
      r.status = DoorwayStatus::kPresent;
    } else if (r.rays_through == 0 && r.blocked_views >= config.closed_min_views) {
      r.status = DoorwayStatus::kClosed;
      r.s_planes.assign(covering.begin(), covering.end());
    }
    out.push_back(r);
  }
  return out;
}

}  // namespace merging
}  // namespace is_graphs
