#include <cmath>
#include <iomanip>
#include <sstream>

#include "is_graphs/agraph/agraph_queries.h"

namespace is_graphs {
namespace agraph {

std::set<int> StoreysOfSurface(const AGraph& graph, const WallSurface& surface) {
  std::set<int> on{surface.storey};
  for (int r : surface.rooms)
    if (r >= 0 && r < static_cast<int>(graph.rooms.size())) on.insert(graph.rooms[r].storey);
  return on;
}

double SignedArea(const std::vector<Eigen::Vector2d>& polygon) {
  double twice_area = 0.0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[(i + 1) % polygon.size()];
    twice_area += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice_area;
}

namespace {

/// The IFC file's length unit, named ("millimetre (0.001 m)"): "%.2f m" printed 0.00 m for it.
std::string UnitName(double metres) {
  const struct {
    double m;
    const char* name;
  } known[] = {{1.0, "metre"},     {0.001, "millimetre"}, {0.01, "centimetre"},
               {0.1, "decimetre"}, {0.3048, "foot"},      {0.0254, "inch"}};
  std::ostringstream out;
  out << std::setprecision(6) << metres << " m";
  for (const auto& k : known)
    if (std::abs(metres - k.m) <= 1e-9 * k.m)
      return k.m == 1.0 ? "metre" : std::string(k.name) + " (" + out.str() + ")";
  return out.str();
}

}  // namespace

std::string Summarize(const AGraph& graph) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(2);
  out << "building: " << (graph.building.empty() ? "(unnamed)" : graph.building) << "\n";
  out << "source:   " << (graph.source.file.empty() ? "(unknown)" : graph.source.file);
  if (!graph.source.schema.empty()) out << ", " << graph.source.schema;
  if (!graph.source.application.empty()) out << ", " << graph.source.application;
  out << ", unit " << UnitName(graph.source.length_unit_m) << "\n";
  out << "mesh:     " << (graph.mesh.empty() ? "(none)" : graph.mesh) << "\n";
  out << "storeys:  " << graph.storeys.size() << "\n";

  for (const Storey& storey : graph.storeys) {
    int x = 0, y = 0, other = 0, walls = 0, doorways = 0, exterior_doorways = 0;
    int by_kind[3] = {0, 0, 0};  // door, opening, virtual
    for (const WallSurface& s : graph.surfaces) {
      if (s.storey != storey.id) continue;
      if (s.orientation == geometry::Orientation::kX) {
        ++x;
      } else if (s.orientation == geometry::Orientation::kY) {
        ++y;
      } else {
        ++other;
      }
    }
    for (const Wall& w : graph.walls) walls += w.storey == storey.id;
    for (const Doorway& d : graph.doorways) {
      if (d.storey != storey.id) continue;
      ++doorways;
      ++by_kind[static_cast<int>(d.kind)];
      exterior_doorways += d.rooms.size() == 1;
    }
    std::vector<const Room*> rooms;
    for (const Room& r : graph.rooms) {
      if (r.storey == storey.id) rooms.push_back(&r);
    }
    out << "storey " << storey.id << " \"" << storey.name << "\" (elevation " << storey.elevation
        << " m, height " << storey.height << " m)\n";
    out << "  wall surfaces: " << x + y + other << " (x " << x << ", y " << y << ", other " << other
        << ")\n";
    out << "  walls:         " << walls << "\n";
    out << "  doorways:      " << doorways << " (" << by_kind[0] << " doors, " << by_kind[1]
        << " openings, " << by_kind[2] << " virtual; " << exterior_doorways << " to outdoors)\n";
    out << "  rooms:         " << rooms.size() << "\n";
    for (const Room* r : rooms) {
      out << "    " << std::setw(3) << r->id << "  " << r->name;
      if (!r->long_name.empty()) out << " \"" << r->long_name << "\"";
      out << "  " << r->area << " m^2, " << r->surfaces.size() << " surfaces, "
          << r->doorways.size() << " doorways";
      if (std::abs(r->floor_z - storey.elevation) > 0.05)  // a split level: its own floor
        out << ", floor " << r->floor_z << " m";
      out << "\n";
    }
    for (const ConversionDrop& d : graph.dropped)
      if (d.storey == storey.id)
        out << "  dropped:       " << d.count << " " << d.ifc_class << " (" << d.reason << ")\n";
  }
  out << "warnings: " << graph.warnings.size() << "\n";
  return out.str();
}

}  // namespace agraph
}  // namespace is_graphs
