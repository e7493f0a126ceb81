#include "is_graphs/agraph/agraph_validation.h"

#include <cmath>
#include <sstream>

namespace is_graphs {
namespace agraph {
namespace {

constexpr double kUnitNormalTolerance = 1e-3;

// Collects the first problem found; later checks are skipped once one is recorded.
class Checker {
 public:
  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }

  void Fail(const std::string& label, const std::string& detail) {
    if (ok()) error_ = label + ": " + detail;
  }
  /// `reference` must index an array of `size` elements called `target`.
  void InRange(const std::string& label, const char* field, int reference, size_t size,
               const char* target) {
    if (reference < 0 || static_cast<size_t>(reference) >= size) {
      std::ostringstream detail;
      detail << field << " refers to " << target << " id " << reference << ", but there are "
             << size << " " << target;
      Fail(label, detail.str());
    }
  }
  void AllInRange(const std::string& label, const char* field, const std::vector<int>& refs,
                  size_t size, const char* target) {
    for (int reference : refs) InRange(label, field, reference, size, target);
  }

 private:
  std::string error_;
};

template <typename Element_t>
std::string LabelOf(const char* array, const Element_t& e, size_t index, const char* ifc_class) {
  return ElementLabel(array, static_cast<int>(index), ifc_class, e.ifc_id);
}

}  // namespace

std::string ElementLabel(const char* array_name, int index, const char* ifc_class, long ifc_id) {
  std::string label = std::string(array_name) + "[" + std::to_string(index) + "]";
  if (ifc_id >= 0) label += std::string(" (") + ifc_class + " #" + std::to_string(ifc_id) + ")";
  return label;
}

std::string ValidateAGraph(const AGraph& g) {
  Checker c;
  const size_t n_storeys = g.storeys.size(), n_surfaces = g.surfaces.size();
  const size_t n_walls = g.walls.size(), n_rooms = g.rooms.size();
  const size_t n_doorways = g.doorways.size();

  for (size_t i = 0; i < n_storeys && c.ok(); ++i) {
    const std::string label = LabelOf("storeys", g.storeys[i], i, "IfcBuildingStorey");
    if (g.storeys[i].id != static_cast<int>(i)) c.Fail(label, "id differs from its index");
  }
  for (size_t i = 0; i < n_surfaces && c.ok(); ++i) {
    const WallSurface& s = g.surfaces[i];
    const std::string label = LabelOf("wall_surfaces", s, i, "IfcWall");
    if (s.id != static_cast<int>(i)) c.Fail(label, "id differs from its index");
    if (std::abs(s.plane.normal.norm() - 1.0) > kUnitNormalTolerance) {
      c.Fail(label, "normal is not a unit vector");
    }
    if (!std::isfinite(s.plane.d)) c.Fail(label, "d is not finite");
    c.InRange(label, "storey", s.storey, n_storeys, "storeys");
    c.InRange(label, "wall", s.wall, n_walls, "walls");
    c.AllInRange(label, "rooms", s.rooms, n_rooms, "rooms");
  }
  for (size_t i = 0; i < n_walls && c.ok(); ++i) {
    const Wall& w = g.walls[i];
    const std::string label = LabelOf("walls", w, i, "IfcWall");
    if (w.id != static_cast<int>(i)) c.Fail(label, "id differs from its index");
    c.InRange(label, "storey", w.storey, n_storeys, "storeys");
    c.InRange(label, "surfaces", w.surface_a, n_surfaces, "wall_surfaces");
    c.InRange(label, "surfaces", w.surface_b, n_surfaces, "wall_surfaces");
    if (w.surface_a == w.surface_b) c.Fail(label, "surfaces must be two distinct ids");
  }
  for (size_t i = 0; i < n_rooms && c.ok(); ++i) {
    const Room& r = g.rooms[i];
    const std::string label = LabelOf("rooms", r, i, "IfcSpace");
    if (r.id != static_cast<int>(i)) c.Fail(label, "id differs from its index");
    if (r.polygon.size() < 3) c.Fail(label, "polygon needs at least 3 vertices");
    c.InRange(label, "storey", r.storey, n_storeys, "storeys");
    c.AllInRange(label, "surfaces", r.surfaces, n_surfaces, "wall_surfaces");
    c.AllInRange(label, "walls", r.walls, n_walls, "walls");
    c.AllInRange(label, "doorways", r.doorways, n_doorways, "doorways");
  }
  for (size_t i = 0; i < n_doorways && c.ok(); ++i) {
    const Doorway& d = g.doorways[i];
    const std::string label = LabelOf("doorways", d, i, "IfcDoor");
    if (d.id != static_cast<int>(i)) c.Fail(label, "id differs from its index");
    c.InRange(label, "storey", d.storey, n_storeys, "storeys");
    if (d.wall != -1) c.InRange(label, "wall", d.wall, n_walls, "walls");
    if (d.rooms.size() != 1 && d.rooms.size() != 2) {
      c.Fail(label, "rooms must hold one or two room ids");
    }
    c.AllInRange(label, "rooms", d.rooms, n_rooms, "rooms");
    if (d.rooms.size() == 2 && d.rooms[0] == d.rooms[1]) {
      c.Fail(label, "rooms lists room " + std::to_string(d.rooms[0]) + " twice");
    }
  }
  // With every reference in range: walls and their surfaces must refer to each other.
  for (size_t i = 0; i < n_walls && c.ok(); ++i) {
    const Wall& w = g.walls[i];
    if (g.surfaces[w.surface_a].wall != w.id || g.surfaces[w.surface_b].wall != w.id) {
      c.Fail(LabelOf("walls", w, i, "IfcWall"),
             "its surfaces do not refer back to it (wall_surfaces[k].wall)");
    }
  }
  for (size_t i = 0; i < n_surfaces && c.ok(); ++i) {
    const WallSurface& s = g.surfaces[i];
    const Wall& w = g.walls[s.wall];
    if (w.surface_a != s.id && w.surface_b != s.id) {
      c.Fail(LabelOf("wall_surfaces", s, i, "IfcWall"),
             "wall " + std::to_string(s.wall) + " does not list this surface");
    }
  }
  return c.error();
}

}  // namespace agraph
}  // namespace is_graphs
