#include "is_graphs/sim/stair_paths.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>

#include "is_graphs/common/disjoint_sets.h"
#include "is_graphs/sim/room_geometry.h"

namespace is_graphs {
namespace sim {
namespace {

// An upward-facing face of a stair object, or a set of them at one height that touch: a tread.
struct Tread {
  double z{0.0};
  double area{0.0};
  Eigen::Vector2d centre{Eigen::Vector2d::Zero()};
  Eigen::Vector2d lo{Eigen::Vector2d::Zero()}, hi{Eigen::Vector2d::Zero()};
  std::vector<Eigen::Vector2d> corners;  // the vertices of its faces
  std::vector<int> objects;              // mesh object indices
};

double BoxGap(const Tread& a, const Tread& b) {
  const Eigen::Vector2d gap = (a.lo - b.hi).cwiseMax(b.lo - a.hi).cwiseMax(0.0);
  return gap.norm();
}

// Joins treads that `touch` into connected sets (union-find), each set merged into one tread or
// returned as the list of its members.
template <typename Touch>
std::vector<std::vector<int>> Components(int n, const Touch& touch) {
  DisjointSets sets_of(n);
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (touch(i, j)) sets_of.Join(i, j);
    }
  }
  std::vector<std::vector<int>> sets(n);
  for (int i = 0; i < n; ++i) sets[sets_of.Find(i)].push_back(i);
  sets.erase(std::remove_if(sets.begin(), sets.end(), [](const auto& s) { return s.empty(); }),
             sets.end());
  return sets;
}

Tread Merge(const std::vector<Tread>& parts, const std::vector<int>& members) {
  Tread t;
  t.lo = parts[members[0]].lo;
  t.hi = parts[members[0]].hi;
  for (int m : members) {
    const Tread& p = parts[m];
    t.z += p.area * p.z;
    t.centre += p.area * p.centre;
    t.area += p.area;
    t.lo = t.lo.cwiseMin(p.lo);
    t.hi = t.hi.cwiseMax(p.hi);
    t.corners.insert(t.corners.end(), p.corners.begin(), p.corners.end());
    for (int o : p.objects) {
      if (std::find(t.objects.begin(), t.objects.end(), o) == t.objects.end())
        t.objects.push_back(o);
    }
  }
  t.z /= t.area;
  t.centre /= t.area;
  return t;
}

// Extent of the tread's corners from its centre along `u` (the farthest corner).
double Reach(const Tread& t, const Eigen::Vector2d& u) {
  double reach = 0.0;
  for (const Eigen::Vector2d& c : t.corners) reach = std::max(reach, (c - t.centre).dot(u));
  return reach;
}

// The storey whose elevation is nearest `z`, within `tolerance`; -1 when none.
int StoreyNear(const agraph::AGraph& graph, double z, double tolerance) {
  int best = -1;
  for (const agraph::Storey& s : graph.storeys) {
    const double d = std::abs(s.elevation - z);
    if (d <= tolerance && (best < 0 || d < std::abs(graph.storeys[best].elevation - z)))
      best = s.id;
  }
  return best;
}

int RoomAt(const agraph::AGraph& graph, int storey, const Eigen::Vector2d& p) {
  for (const agraph::Room& r : graph.rooms) {
    if (r.storey == storey && PointInPolygon(r.polygon, p)) return r.id;
  }
  return -1;
}

// Douglas-Peucker in x-y: the points of `line` (first and last kept) off the simplified line by
// more than `tolerance`.
std::vector<Eigen::Vector3d> Simplified(const std::vector<Eigen::Vector3d>& line,
                                        double tolerance) {
  if (line.size() <= 2) return line;
  const Eigen::Vector2d a = line.front().head<2>(), b = line.back().head<2>();
  double worst = -1.0;
  std::size_t at = 0;
  for (std::size_t i = 1; i + 1 < line.size(); ++i) {
    const Eigen::Vector2d p = line[i].head<2>();
    const Eigen::Vector2d ab = b - a;
    const double t =
        ab.squaredNorm() > 1e-12 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
    const double d = (p - (a + t * ab)).norm();
    if (d > worst) worst = d, at = i;
  }
  if (worst <= tolerance) return {line.front(), line.back()};
  std::vector<Eigen::Vector3d> left = Simplified({line.begin(), line.begin() + at + 1}, tolerance);
  const std::vector<Eigen::Vector3d> right = Simplified({line.begin() + at, line.end()}, tolerance);
  left.insert(left.end(), right.begin() + 1, right.end());
  return left;
}

std::string Fmt(const Eigen::Vector2d& p) {
  std::ostringstream s;
  s.precision(2);
  s << std::fixed << "(" << p.x() << ", " << p.y() << ")";
  return s.str();
}

}  // namespace

std::string StairPathConfig::Validate() const {
  if (!(min_tread_area > 0.0)) return "min_tread_area: must be > 0 m²";
  if (!(max_rise > 0.0 && max_rise <= 1.0)) return "max_rise: must be in (0, 1] m";
  if (!(max_gap >= 0.0)) return "max_gap: must be >= 0 m";
  if (!(floor_clearance > 0.0)) return "floor_clearance: must be > 0 m";
  if (!(storey_tolerance > 0.0)) return "storey_tolerance: must be > 0 m";
  if (!(min_width >= 0.0)) return "min_width: must be >= 0 m";
  return "";
}

double StairPath::Length() const {
  double length = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i)
    length += (points[i] - points[i - 1]).head<2>().norm();
  return length;
}

std::vector<StairPath> FindStairPaths(const geometry::TriangleMesh& mesh,
                                      const agraph::AGraph& graph, const StairPathConfig& config,
                                      std::vector<std::string>* skipped) {
  std::vector<StairPath> paths;
  std::set<std::string> fragments;
  auto skip = [&](const std::string& line) {
    if (skipped) skipped->push_back(line);
  };
  if (const std::string e = config.Validate(); !e.empty()) {
    skip("stair search not run: " + e);
    return paths;
  }
  // Upward faces of the stair objects, joined per object into flat pieces at one height.
  std::vector<Tread> faces;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const int object = mesh.triangle_object.empty() ? -1 : mesh.triangle_object[i];
    if (object < 0) continue;
    const std::string cls = mesh.ObjectClass(object);
    if (cls != "IfcStair" && cls != "IfcStairFlight") continue;
    const Eigen::Vector3i& t = mesh.triangles[i];
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    const Eigen::Vector3d& b = mesh.vertices[t[1]];
    const Eigen::Vector3d& c = mesh.vertices[t[2]];
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double area = 0.5 * n.norm();
    if (area < 1e-6 || n.z() < 0.95 * n.norm()) continue;  // not facing up
    Tread f;
    f.z = (a.z() + b.z() + c.z()) / 3.0;
    f.area = area;
    f.centre = ((a + b + c) / 3.0).head<2>();
    f.corners = {a.head<2>(), b.head<2>(), c.head<2>()};
    f.lo = a.head<2>().cwiseMin(b.head<2>()).cwiseMin(c.head<2>());
    f.hi = a.head<2>().cwiseMax(b.head<2>()).cwiseMax(c.head<2>());
    f.objects = {object};
    faces.push_back(f);
  }
  std::vector<Tread> treads;
  for (const auto& set : Components(static_cast<int>(faces.size()), [&](int i, int j) {
         return std::abs(faces[i].z - faces[j].z) < 0.02 && BoxGap(faces[i], faces[j]) < 0.01;
       })) {
    Tread t = Merge(faces, set);
    if (t.area >= config.min_tread_area) treads.push_back(std::move(t));
  }
  // Stairs: treads one rise apart whose outlines touch (a flight, its landings, the next flight).
  for (auto set : Components(static_cast<int>(treads.size()), [&](int i, int j) {
         const double rise = std::abs(treads[i].z - treads[j].z);
         return rise > 0.02 && rise <= config.max_rise &&
                BoxGap(treads[i], treads[j]) <= config.max_gap;
       })) {
    std::sort(set.begin(), set.end(), [&](int a, int b) { return treads[a].z < treads[b].z; });
    // Pieces of one step at one height (a tread split by a stringer, a landing in parts): one.
    std::vector<Tread> steps;
    for (std::size_t k = 0; k < set.size();) {
      std::size_t e = k + 1;
      while (e < set.size() && treads[set[e]].z - treads[set[k]].z < 0.02) ++e;
      steps.push_back(Merge(treads, std::vector<int>(set.begin() + k, set.begin() + e)));
      k = e;
    }
    StairPath path;
    std::vector<int> objects;
    for (const Tread& t : steps) {
      for (int o : t.objects) {
        if (std::find(objects.begin(), objects.end(), o) == objects.end()) objects.push_back(o);
      }
    }
    std::sort(objects.begin(), objects.end());
    for (int o : objects) path.name += (path.name.empty() ? "" : "+") + mesh.object_names[o];
    if (steps.size() < 3) {  // one line per object (a stair's loose parts: nosings, a kerb)
      if (fragments.insert(path.name).second)
        skip(path.name + ": parts of 1 or 2 steps alone, not a flight");
      continue;
    }
    const Tread& bottom = steps.front();
    const Tread& top = steps.back();
    const double rise_bottom = steps[1].z - bottom.z;
    const double rise_top = top.z - steps[steps.size() - 2].z;
    Eigen::Vector2d u0 = steps[1].centre - bottom.centre;
    Eigen::Vector2d u1 = top.centre - steps[steps.size() - 2].centre;
    if (u0.norm() < 1e-3 || u1.norm() < 1e-3) {
      skip(path.name + ": its end treads do not lead anywhere (no walking direction)");
      continue;
    }
    u0.normalize();
    u1.normalize();
    // The narrowest tread across the walking direction (landings are wide anyway).
    path.width = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < steps.size(); ++k) {
      const Eigen::Vector2d& prev = steps[k == 0 ? 0 : k - 1].centre;
      const Eigen::Vector2d& next = steps[std::min(k + 1, steps.size() - 1)].centre;
      Eigen::Vector2d u = next - prev;
      if (u.norm() < 1e-3) continue;
      u.normalize();
      const Eigen::Vector2d across(-u.y(), u.x());
      const Tread& t = steps[k];
      path.width = std::min(path.width, Reach(t, across) + Reach(t, -across));
    }
    const Eigen::Vector2d foot = bottom.centre - (Reach(bottom, -u0) + config.floor_clearance) * u0;
    const Eigen::Vector2d head = top.centre + (Reach(top, u1) + config.floor_clearance) * u1;
    const double foot_z = bottom.z - rise_bottom, head_z = top.z + rise_top;
    path.lower_storey = StoreyNear(graph, foot_z, config.storey_tolerance);
    path.upper_storey = StoreyNear(graph, head_z, config.storey_tolerance);
    if (path.width < config.min_width) {
      std::ostringstream s;
      s.precision(2);
      s << std::fixed << path.name << ": " << path.width << " m wide, under min_width "
        << config.min_width << " m (a spiral or winders too tight for the robot)";
      skip(s.str());
      continue;
    }
    if (path.lower_storey < 0 || path.upper_storey < 0 || path.lower_storey == path.upper_storey) {
      std::ostringstream s;
      s.precision(2);
      s << std::fixed << path.name << ": from z " << foot_z << " to " << head_z
        << " m, not from one storey's floor to another's";
      skip(s.str());
      continue;
    }
    path.lower_room = RoomAt(graph, path.lower_storey, foot);
    if (path.lower_room < 0) path.lower_room = RoomAt(graph, path.lower_storey, bottom.centre);
    path.upper_room = RoomAt(graph, path.upper_storey, head);
    if (path.upper_room < 0) path.upper_room = RoomAt(graph, path.upper_storey, top.centre);
    if (path.lower_room < 0 || path.upper_room < 0) {
      skip(path.name + ": its " +
           (path.lower_room < 0 ? "foot " + Fmt(foot) : "head " + Fmt(head)) +
           " is in no room of storey '" +
           graph.storeys[path.lower_room < 0 ? path.lower_storey : path.upper_storey].name + "'");
      continue;
    }
    // The walk: the foot, the step centres where the way turns (landings; Douglas-Peucker in
    // x-y, 0.1 m), the head.
    path.points.push_back({foot.x(), foot.y(), foot_z});
    std::vector<Eigen::Vector3d> centres;
    for (const Tread& t : steps) centres.push_back({t.centre.x(), t.centre.y(), t.z});
    for (const Eigen::Vector3d& p : Simplified(centres, 0.1)) path.points.push_back(p);
    path.points.push_back({head.x(), head.y(), head_z});
    std::vector<Eigen::Vector2d> corners;
    for (const Tread& t : steps) corners.insert(corners.end(), t.corners.begin(), t.corners.end());
    path.footprint = ConvexHull(corners);
    paths.push_back(std::move(path));
  }
  std::sort(paths.begin(), paths.end(),
            [](const StairPath& a, const StairPath& b) { return a.name < b.name; });
  return paths;
}

}  // namespace sim
}  // namespace is_graphs
