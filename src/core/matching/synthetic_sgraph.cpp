#include "is_graphs/matching/synthetic_sgraph.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/synthetic_walk.h"
#include "is_graphs/sgraph/doorway_detection.h"

namespace is_graphs {
namespace matching {
namespace {

struct Rect {
  Eigen::Vector2d long_axis{Eigen::Vector2d::UnitX()};
  double length{0.0};
  double width{0.0};
};

/// The smallest rectangle around the room's footprint over the directions of its surfaces.
Rect BoundingRect(const agraph::AGraph& b, const agraph::Room& room) {
  Rect best;
  double best_area = std::numeric_limits<double>::infinity();
  for (int sid : room.surfaces) {
    if (sid < 0 || sid >= static_cast<int>(b.surfaces.size())) continue;
    Eigen::Vector2d u = b.surfaces[sid].plane.normal.head<2>();
    if (u.norm() < 0.5 || room.polygon.size() < 3) continue;
    u.normalize();
    const Eigen::Vector2d v(-u.y(), u.x());
    double umin = 1e18, umax = -1e18, vmin = 1e18, vmax = -1e18;
    for (const auto& p : room.polygon) {
      umin = std::min(umin, p.dot(u)), umax = std::max(umax, p.dot(u));
      vmin = std::min(vmin, p.dot(v)), vmax = std::max(vmax, p.dot(v));
    }
    const double du = umax - umin, dv = vmax - vmin;
    if (du * dv < best_area) {
      best_area = du * dv;
      best = du > dv ? Rect{u, du, dv} : Rect{v, dv, du};
    }
  }
  return best;
}

geometry::Plane Mirror(const geometry::Plane& p) {
  return geometry::Plane(Eigen::Vector3d(-p.normal.x(), p.normal.y(), p.normal.z()), p.d);
}

Eigen::Vector3d Mirror(const Eigen::Vector3d& p) { return {-p.x(), p.y(), p.z()}; }

}  // namespace

bool IsCorridorLike(const agraph::AGraph& building, int room, double min_aspect) {
  if (min_aspect <= 0.0 || room < 0 || room >= static_cast<int>(building.rooms.size()))
    return false;
  const Rect r = BoundingRect(building, building.rooms[room]);
  return r.width > 0.0 && r.length / r.width >= min_aspect;
}

Eigen::Isometry3d RandomPlanarMotion(std::mt19937_64& rng, double max_translation) {
  std::uniform_real_distribution<double> yaw(-M_PI, M_PI), t(-max_translation, max_translation);
  const double a = yaw(rng), x = t(rng), y = t(rng);
  return geometry::IsometryFromXYYaw(x, y, a);
}

std::vector<int> RandomConnectedRooms(const agraph::AGraph& b, int count, std::mt19937_64& rng) {
  const int n = static_cast<int>(b.rooms.size());
  count = std::min(count, n);
  std::vector<int> chosen;
  if (count <= 0) return chosen;
  std::set<int> in;
  chosen.push_back(std::uniform_int_distribution<int>(0, n - 1)(rng));
  in.insert(chosen.back());
  while (static_cast<int>(chosen.size()) < count) {
    std::vector<int> frontier;
    for (int r : chosen)
      for (int did : b.rooms[r].doorways)
        if (did >= 0 && did < static_cast<int>(b.doorways.size()))
          for (int other : b.doorways[did].rooms)
            if (other >= 0 && other < n && !in.count(other)) frontier.push_back(other);
    std::sort(frontier.begin(), frontier.end());
    frontier.erase(std::unique(frontier.begin(), frontier.end()), frontier.end());
    int next = -1;
    if (!frontier.empty()) {
      next = frontier[std::uniform_int_distribution<size_t>(0, frontier.size() - 1)(rng)];
    } else {  // no doorway left: the nearest room not taken
      double best = std::numeric_limits<double>::infinity();
      for (int r = 0; r < n; ++r) {
        if (in.count(r)) continue;
        const double d = (b.rooms[r].center - b.rooms[chosen.front()].center).norm();
        if (d < best) best = d, next = r;
      }
    }
    chosen.push_back(next);
    in.insert(next);
  }
  return chosen;
}

SyntheticSGraph MakeSyntheticSGraph(const agraph::AGraph& b, const SyntheticSGraphConfig& config) {
  SyntheticSGraph out;
  out.bim_T_map = geometry::ProjectToYawOnly(config.bim_T_map);
  const Eigen::Isometry3d map_T_bim = out.bim_T_map.inverse();
  std::mt19937_64 rng(config.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  sgraph::SGraph& g = out.graph;
  g.revision = 1;

  std::vector<int> rooms = config.rooms;
  if (rooms.empty())
    for (const auto& r : b.rooms) rooms.push_back(r.id);

  // One deviation per A-surface (the building as built), drawn in surface order.
  std::vector<double> deviation(b.surfaces.size(), 0.0);
  for (auto& d : deviation) d = config.bim_deviation * (2.0 * unit(rng) - 1.0);

  // Harsh deviations, from their own stream: walls of the taken rooms moved, turned, missing.
  std::mt19937_64 harsh(config.seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull);
  std::uniform_real_distribution<double> harsh_unit(0.0, 1.0);
  {
    std::set<int> candidates;
    for (int rid : rooms)
      if (rid >= 0 && rid < static_cast<int>(b.rooms.size()))
        for (int sid : b.rooms[rid].surfaces)
          if (sid >= 0 && sid < static_cast<int>(b.surfaces.size())) candidates.insert(sid);
    std::vector<int> order(candidates.begin(), candidates.end());
    std::shuffle(order.begin(), order.end(), harsh);
    size_t next = 0;
    auto sign = [&] { return harsh_unit(harsh) < 0.5 ? -1.0 : 1.0; };
    for (int k = 0; k < config.moved_walls && next < order.size(); ++k)
      out.moved[order[next++]] =
          sign() * (config.moved_wall_min +
                    (config.moved_wall_max - config.moved_wall_min) * harsh_unit(harsh));
    for (int k = 0; k < config.turned_walls && next < order.size(); ++k)
      out.turned[order[next++]] =
          sign() * config.turned_wall_deg * M_PI / 180.0 * harsh_unit(harsh);
    for (int k = 0; k < config.missing_walls && next < order.size(); ++k)
      out.missing.push_back(order[next++]);
  }
  auto lookup = [](const std::map<int, double>& m, int id) {
    const auto it = m.find(id);
    return it == m.end() ? 0.0 : it->second;
  };

  // Noise turns a plane about the middle of the surface (where it was seen), not about the origin.
  // A long plane is fitted to points along all of it, so its direction is better known: the
  // turn is bounded so that its ends move by at most 10 cm.
  auto to_map = [&](const geometry::Plane& bim_plane, const Eigen::Vector3d& bim_middle,
                    double length) {
    geometry::Plane p = bim_plane.Transformed(map_T_bim);
    if (config.normal_noise_deg > 0.0) {
      const double bound = std::atan2(0.1, 0.5 * std::max(length, 0.2));
      const double a =
          std::clamp(config.normal_noise_deg * M_PI / 180.0 * gauss(rng), -bound, bound);
      const Eigen::Vector3d pivot = p.Project(map_T_bim * bim_middle);
      p.normal = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()) * p.normal;
      p.d = p.normal.dot(pivot);
    }
    p.d += config.offset_noise * gauss(rng);
    return config.mirror ? Mirror(p) : p;
  };
  auto point_to_map = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d q = map_T_bim * p;
    return config.mirror ? Mirror(q) : q;
  };

  std::map<int, int> shared_plane;  // A-surface id -> S-plane id (when not split)
  int next_plane = 5;
  auto add_plane = [&](const agraph::WallSurface& s) {
    sgraph::Plane p;
    p.id = next_plane;
    next_plane += 3;  // ids stable but not dense
    const Eigen::Vector2d middle = 0.5 * (s.start + s.end);
    const Eigen::Vector3d middle3(middle.x(), middle.y(), 0.5 * (s.z_min + s.z_max));
    // As built: turned about its middle, moved along its normal (harsh), plus the deviation.
    const Eigen::AngleAxisd turn(lookup(out.turned, s.id), Eigen::Vector3d::UnitZ());
    const double moved = lookup(out.moved, s.id);
    const Eigen::Vector3d n = turn * s.plane.normal;
    const double d = s.plane.d + n.dot(middle3) - s.plane.normal.dot(middle3);
    const geometry::Plane built(n, d + deviation[s.id] + moved);
    auto built_point = [&](const Eigen::Vector2d& q) -> Eigen::Vector2d {
      const Eigen::Vector3d p3 =
          middle3 + turn * Eigen::Vector3d(q.x() - middle.x(), q.y() - middle.y(), 0.0) + moved * n;
      return point_to_map(Eigen::Vector3d(p3.x(), p3.y(), 0)).head<2>();
    };
    p.plane = to_map(built, middle3, s.Length());
    p.orientation = geometry::ClassifyOrientation(p.plane.normal);
    p.start = built_point(s.start);
    p.end = built_point(s.end);
    p.z_min = s.z_min, p.z_max = s.z_max;
    p.num_points = 1000;
    p.covariance = Eigen::Matrix4d::Identity() * 1e-4;
    g.planes.push_back(p);
    out.plane_truth[p.id] = s.id;
    return p.id;
  };

  int next_room = 3;
  for (int rid : rooms) {
    if (rid < 0 || rid >= static_cast<int>(b.rooms.size())) continue;
    const agraph::Room& a = b.rooms[rid];
    std::vector<int> surfaces = a.surfaces;
    sgraph::Room r;
    r.id = next_room;
    next_room += 2;
    Eigen::Vector3d centre = a.center;
    const Rect rect = BoundingRect(b, a);
    if (IsCorridorLike(b, rid, config.corridor_aspect)) {
      // Two opposed planes: the longest surface on each side of the long axis.
      const Eigen::Vector2d across(-rect.long_axis.y(), rect.long_axis.x());
      int side[2] = {-1, -1};
      for (int sid : a.surfaces) {
        const Eigen::Vector2d n = b.surfaces[sid].plane.normal.head<2>();
        const int k = n.dot(across) > 0.95 ? 0 : (n.dot(across) < -0.95 ? 1 : -1);
        if (k >= 0 && (side[k] < 0 || b.surfaces[sid].Length() > b.surfaces[side[k]].Length()))
          side[k] = sid;
      }
      if (side[0] >= 0 && side[1] >= 0) {
        r.type = sgraph::RoomType::kCorridor;
        surfaces = {side[0], side[1]};
        // The centre on the mid-line, somewhere along the axis.
        const auto& p0 = b.surfaces[side[0]].plane;
        const auto& p1 = b.surfaces[side[1]].plane;
        const Eigen::Vector3d n0 = p0.normal;
        const double mid = 0.5 * (p0.d - p1.d);  // n0·p at the mid-line (p1.normal ≈ -n0)
        centre += (mid - n0.dot(centre)) * n0;
        const double shift = config.corridor_shift * 0.5 * (rect.length - rect.width);
        centre.head<2>() += rect.long_axis * shift * (2.0 * unit(rng) - 1.0);
      }
    }
    for (int sid : surfaces) {
      if (sid < 0 || sid >= static_cast<int>(b.surfaces.size())) continue;
      if (std::find(out.missing.begin(), out.missing.end(), sid) != out.missing.end()) continue;
      const bool split = b.surfaces[sid].rooms.size() > 1 && unit(rng) < config.split_probability;
      auto it = shared_plane.find(sid);
      if (split || it == shared_plane.end()) {
        const int pid = add_plane(b.surfaces[sid]);
        if (!split) shared_plane[sid] = pid;
        r.planes.push_back(pid);
      } else {
        r.planes.push_back(it->second);
      }
    }
    centre.head<2>() += config.centre_noise * Eigen::Vector2d(gauss(rng), gauss(rng));
    r.center = point_to_map(centre);
    g.rooms.push_back(r);
    out.room_truth[r.id] = rid;
  }

  // Clutter: a plane inside a room, at a random direction (a cupboard, a partition screen).
  for (int k = 0; k < config.extra_planes && !g.rooms.empty(); ++k) {
    auto& r = g.rooms[std::uniform_int_distribution<size_t>(0, g.rooms.size() - 1)(rng)];
    const double a = 2.0 * M_PI * unit(rng);
    const Eigen::Vector3d n(std::cos(a), std::sin(a), 0.0);
    sgraph::Plane p;
    p.id = next_plane;
    next_plane += 3;
    p.plane = geometry::Plane::FromPointNormal(r.center - (0.3 + 0.7 * unit(rng)) * n, n);
    p.orientation = geometry::ClassifyOrientation(n);
    const Eigen::Vector2d foot = p.plane.Project(r.center).head<2>();
    const Eigen::Vector2d along(-n.y(), n.x());
    const double half = 0.5 + 0.75 * harsh_unit(harsh);
    p.start = foot - half * along, p.end = foot + half * along;
    p.z_min = 0.0, p.z_max = 1.2 + harsh_unit(harsh);
    p.num_points = 300;
    g.planes.push_back(p);
    r.planes.push_back(p.id);
  }

  // Rooms that are not in the BIM: rectangles near the others.
  Eigen::Vector2d lo(1e18, 1e18), hi(-1e18, -1e18);
  for (const auto& r : g.rooms)
    lo = lo.cwiseMin(r.center.head<2>()), hi = hi.cwiseMax(r.center.head<2>());
  if (g.rooms.empty()) lo = hi = Eigen::Vector2d::Zero();
  for (int k = 0; k < config.extra_rooms; ++k) {
    const Eigen::Vector2d c(lo.x() - 5.0 + (hi.x() - lo.x() + 10.0) * unit(rng),
                            lo.y() - 5.0 + (hi.y() - lo.y() + 10.0) * unit(rng));
    const double a = 2.0 * M_PI * unit(rng);
    const double half[2] = {1.25 + 2.0 * unit(rng), 1.25 + 2.0 * unit(rng)};
    sgraph::Room r;
    r.id = next_room;
    next_room += 2;
    r.center = Eigen::Vector3d(c.x(), c.y(), 1.4);
    for (int side = 0; side < 4; ++side) {
      const double t = a + side * M_PI / 2.0;
      const Eigen::Vector3d n(std::cos(t), std::sin(t), 0.0);  // pointing inside
      sgraph::Plane p;
      p.id = next_plane;
      next_plane += 3;
      p.plane = geometry::Plane::FromPointNormal(r.center - half[side % 2] * n, n);
      p.orientation = geometry::ClassifyOrientation(n);
      const Eigen::Vector2d foot = (r.center - half[side % 2] * n).head<2>();
      const Eigen::Vector2d along(-n.y(), n.x());
      p.start = foot - half[(side + 1) % 2] * along, p.end = foot + half[(side + 1) % 2] * along;
      p.z_min = 0.0, p.z_max = 2.8;
      p.num_points = 1000;
      g.planes.push_back(p);
      r.planes.push_back(p.id);
    }
    g.rooms.push_back(r);
  }

  // The walk: keyframes in M, each chain joined keyframe to keyframe.
  if (config.walk) {
    const auto chains = SyntheticWalk(b, rooms, config.walk_spacing, config.through_walls, harsh);
    std::normal_distribution<double> walk_noise(0.0, config.walk_noise);
    int id = 0;
    for (const auto& chain : chains)
      for (size_t i = 0; i < chain.size(); ++i) {
        sgraph::Keyframe k;
        k.id = id++;
        k.previous = i == 0 ? -1 : k.id - 1;
        k.stamp = k.id;
        Eigen::Vector3d p = point_to_map(Eigen::Vector3d(chain[i].x(), chain[i].y(), 0.0));
        if (config.walk_noise > 0.0)
          p.head<2>() += Eigen::Vector2d(walk_noise(harsh), walk_noise(harsh));
        k.pose.translation() = p;
        g.keyframes.push_back(k);
      }
  }

  // Walls of rooms not taken, seen through doorways: planes of no room, each a part of its
  // surface. Last, so that the draws above are the same with or without them.
  for (int rid : config.seen_rooms) {
    if (rid < 0 || rid >= static_cast<int>(b.rooms.size())) continue;
    for (int sid : b.rooms[rid].surfaces) {
      if (sid < 0 || sid >= static_cast<int>(b.surfaces.size()) || shared_plane.count(sid))
        continue;
      shared_plane[sid] = add_plane(b.surfaces[sid]);
      sgraph::Plane& p = g.planes.back();
      const double share = 0.4 + 0.6 * harsh_unit(harsh);
      const double from = (1.0 - share) * harsh_unit(harsh);
      const Eigen::Vector2d a = p.start, ab = p.end - p.start;
      p.start = a + from * ab, p.end = a + (from + share) * ab;
    }
  }

  if (config.observations && config.walk && !config.mirror)
    AddSyntheticObservations(b, config, out);

  // Doorways from the walk, as the S-Graph node finds them; some missed, some where the BIM
  // has none (an opening cut on site). Their own stream: the graph above is the same without.
  if (config.doorways) {
    std::mt19937_64 doors(config.seed ^ 0xD0025ull);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<sgraph::Doorway> kept;
    for (auto& d : sgraph::DetectDoorways(g, sgraph::DoorwayConfig{}))
      if (unit(doors) >= config.missing_doorway_share) kept.push_back(std::move(d));
    for (int k = 0; k < config.extra_doorways && !g.rooms.empty(); ++k) {
      const sgraph::Room& r =
          g.rooms[std::uniform_int_distribution<size_t>(0, g.rooms.size() - 1)(doors)];
      if (r.planes.empty()) continue;
      const int pid =
          r.planes[std::uniform_int_distribution<size_t>(0, r.planes.size() - 1)(doors)];
      const auto p = std::find_if(g.planes.begin(), g.planes.end(),
                                  [&](const sgraph::Plane& q) { return q.id == pid; });
      if (p == g.planes.end()) continue;
      sgraph::Doorway d;
      d.id = 1000000 + k;
      const Eigen::Vector2d at = p->start + unit(doors) * (p->end - p->start);
      d.position = Eigen::Vector3d(at.x(), at.y(), p->z_min);
      d.width = unit(doors) < 0.5 ? 0.0 : 0.7 + 0.6 * unit(doors);
      d.rooms = {r.id};
      d.planes = {pid};
      kept.push_back(d);
    }
    g.doorways = std::move(kept);
  }
  return out;
}

}  // namespace matching
}  // namespace is_graphs
