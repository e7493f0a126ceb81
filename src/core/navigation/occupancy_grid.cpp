#include "is_graphs/navigation/occupancy_grid.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>

#include "grid_raster.h"

namespace is_graphs {
namespace navigation {
namespace {

using Polygon = std::vector<Eigen::Vector2d>;

/// A planned wall moved (or removed) as built: the 2-D motion of its footprint.
struct WallChange {
  bool removed{false};
  Eigen::Isometry2d motion{Eigen::Isometry2d::Identity()};
};

Polygon Moved(const Polygon& polygon, const Eigen::Isometry2d& motion) {
  Polygon out;
  for (const auto& p : polygon) out.push_back(motion * p);
  return out;
}

Eigen::Vector2d Middle(const Polygon& polygon) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const auto& p : polygon) sum += p;
  return polygon.empty() ? sum : Eigen::Vector2d(sum / polygon.size());
}

/// The storey wall a deviation names: same GlobalId (any wall when it has none), the nearest
/// mid-line middle, within 0.5 m; -1 when none.
int MatchWall(const agraph::AGraph& graph, const merging::WallDeviation& d) {
  const Eigen::Vector2d mid = 0.5 * (d.start + d.end);
  int best = -1;
  double best_distance = 0.5;
  for (const auto& w : graph.walls) {
    if (!d.guid.empty() && w.guid != d.guid) continue;
    const double distance = (Middle(WallFootprint(graph, w)) - mid).norm();
    if (distance < best_distance) best = w.id, best_distance = distance;
  }
  return best;
}

std::vector<WallChange> WallChanges(const agraph::AGraph& graph,
                                    const std::vector<merging::WallDeviation>* deviations) {
  std::vector<WallChange> changes(graph.walls.size());
  if (!deviations) return changes;
  for (const auto& d : *deviations) {
    if (d.status != merging::WallStatus::kMoved && d.status != merging::WallStatus::kNotBuilt)
      continue;
    const int id = MatchWall(graph, d);
    if (id < 0) continue;
    const auto& wall = graph.walls[id];
    changes[id].removed = d.status == merging::WallStatus::kNotBuilt;
    if (d.status != merging::WallStatus::kMoved || wall.surface_a < 0) continue;
    const Eigen::Vector2d centre = Middle(WallFootprint(graph, wall));
    const Eigen::Vector2d normal =
        graph.surfaces[wall.surface_a].plane.normal.head<2>().normalized();
    changes[id].motion = Eigen::Translation2d(centre + d.offset * normal) *
                         Eigen::Rotation2Dd(d.angle) * Eigen::Translation2d(-centre);
  }
  return changes;
}

bool SurfaceInBand(const agraph::WallSurface& s, double z0, double z1) {
  return s.z_max >= z0 && s.z_min <= z1;
}

/// The wall's faces and footprint, occupied, when any face reaches into the band.
void DrawWall(const agraph::AGraph& graph, const agraph::Wall& wall, const Eigen::Isometry2d& m,
              double z0, double z1, GridRaster& raster) {
  bool in_band = false;
  for (int sid : {wall.surface_a, wall.surface_b})
    if (sid >= 0 && SurfaceInBand(graph.surfaces[sid], z0, z1)) in_band = true;
  if (!in_band) return;
  raster.FillPolygon(Moved(WallFootprint(graph, wall), m), OccupancyGrid::kOccupied);
  for (int sid : {wall.surface_a, wall.surface_b}) {
    if (sid < 0) continue;
    const auto& s = graph.surfaces[sid];
    raster.MarkSegment(m * s.start, m * s.end, OccupancyGrid::kOccupied);
  }
}

/// Every mesh element's section in the band, occupied, but what a robot passes or what moves
/// (kPassable), and the elements of `skipped_ifc_ids`.
void DrawMesh(const geometry::TriangleMesh& mesh, double z0, double z1,
              const std::set<long>& skipped_ifc_ids, GridRaster& raster) {
  // Doors (open), what is no element, furniture (moves), coverings (finishes on floors and walls,
  // whose walls are drawn), the site's terrain.
  static const std::set<std::string> kPassable = {"IfcDoor",
                                                  "IfcSpace",
                                                  "IfcOpeningElement",
                                                  "IfcVirtualElement",
                                                  "IfcFurnishingElement",
                                                  "IfcFurniture",
                                                  "IfcSystemFurnitureElement",
                                                  "IfcCovering",
                                                  "IfcSite",
                                                  "IfcGeographicElement",
                                                  "IfcAnnotation"};
  std::vector<int> object_skipped(mesh.object_names.size(), -1);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const int object = mesh.triangle_object[t];
    if (object >= 0 && object_skipped[object] < 0) {
      const std::string& name = mesh.object_names[object];
      const size_t hash = name.find('#');
      const long ifc_id = hash == std::string::npos ? -1 : std::atol(name.c_str() + hash + 1);
      object_skipped[object] =
          kPassable.count(mesh.ObjectClass(object)) || skipped_ifc_ids.count(ifc_id) ? 1 : 0;
    }
    if (object >= 0 && object_skipped[object] == 1) continue;
    const auto& tri = mesh.triangles[t];
    raster.FillSection({mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]}, z0,
                       z1, OccupancyGrid::kOccupied);
  }
}

/// The direction of the room outline edge nearest to `p` among the doorway's rooms (a door whose
/// wall stands on another storey, as the exporter modelled it); zero when it has no rooms.
Eigen::Vector2d NearestOutlineDirection(const agraph::AGraph& graph, const agraph::Doorway& d) {
  Eigen::Vector2d best = Eigen::Vector2d::Zero();
  double best_distance = std::numeric_limits<double>::infinity();
  const Eigen::Vector2d p = d.position.head<2>();
  for (int room : d.rooms) {
    if (room < 0 || room >= static_cast<int>(graph.rooms.size())) continue;
    const auto& poly = graph.rooms[room].polygon;
    for (size_t i = 0; i < poly.size(); ++i) {
      const Eigen::Vector2d a = poly[i], ab = poly[(i + 1) % poly.size()] - a;
      if (ab.squaredNorm() < 1e-12) continue;
      const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      const double distance = (a + t * ab - p).norm();
      if (distance < best_distance) best_distance = distance, best = ab.normalized();
    }
  }
  return best;
}

/// The doorway's passage: its width along the wall, across the wall and 10 cm either side (a
/// door whose wall is not on the storey: across the room outline nearest to it, 30 cm each way).
Polygon DoorwayPassage(const agraph::AGraph& graph, const agraph::Doorway& d, double width) {
  Eigen::Vector2d p = d.position.head<2>(), t = Eigen::Vector2d::Zero();
  double across = 0.3;
  if (d.wall >= 0 && d.wall < static_cast<int>(graph.walls.size()) &&
      graph.walls[d.wall].surface_a >= 0) {
    const auto& wall = graph.walls[d.wall];
    const Eigen::Vector2d n = graph.surfaces[wall.surface_a].plane.normal.head<2>().normalized();
    t = Eigen::Vector2d(-n.y(), n.x());
    // On the wall's mid-plane, wherever across the wall the IFC placed the door.
    const Eigen::Vector2d mid = Middle(WallFootprint(graph, wall));
    p -= n * n.dot(p - mid);
    across = 0.5 * wall.thickness + 0.1;
  } else {
    t = NearestOutlineDirection(graph, d);
  }
  if (t.isZero()) return {};
  const Eigen::Vector2d n(-t.y(), t.x());
  const double along = 0.5 * width;
  return {p - along * t - across * n, p + along * t - across * n, p + along * t + across * n,
          p - along * t + across * n};
}

}  // namespace

std::string GridConfig::Validate() const {
  if (!(resolution > 0.0 && resolution <= 1.0)) return "resolution: must be in (0, 1] m";
  if (!(slice_max > slice_min)) return "slice_max: must be above slice_min";
  if (!(margin >= 0.0)) return "margin: must be >= 0";
  if (!(door_default_width > 0.0)) return "door_default_width: must be > 0";
  if (!(extra_thickness > 0.0)) return "extra_thickness: must be > 0";
  return "";
}

Eigen::Vector2i OccupancyGrid::CellOf(const Eigen::Vector2d& p) const {
  return Eigen::Vector2i(static_cast<int>(std::floor((p.x() - origin.x()) / resolution)),
                         static_cast<int>(std::floor((p.y() - origin.y()) / resolution)));
}

Eigen::Vector2d OccupancyGrid::CentreOf(int ix, int iy) const {
  return origin + resolution * Eigen::Vector2d(ix + 0.5, iy + 0.5);
}

bool OccupancyGrid::OccupiedNear(const Eigen::Vector2d& p, int n) const {
  const Eigen::Vector2i c = CellOf(p);
  for (int dy = -n; dy <= n; ++dy)
    for (int dx = -n; dx <= n; ++dx)
      if (Contains(c.x() + dx, c.y() + dy) && At(c.x() + dx, c.y() + dy) == kOccupied) return true;
  return false;
}

std::vector<Eigen::Vector2d> WallFootprint(const agraph::AGraph& graph, const agraph::Wall& wall) {
  if (wall.surface_a < 0 || wall.surface_b < 0) return {};
  const auto& a = graph.surfaces[wall.surface_a];
  const auto& b = graph.surfaces[wall.surface_b];
  // b's tangent runs against a's: a.start, a.end, b.start, b.end go round the footprint.
  return {a.start, a.end, b.start, b.end};
}

Eigen::Vector3i CountCells(const OccupancyGrid& grid) {
  Eigen::Vector3i counts = Eigen::Vector3i::Zero();
  for (const auto c : grid.cells)
    ++counts[c == OccupancyGrid::kFree ? 0 : c == OccupancyGrid::kOccupied ? 1 : 2];
  return counts;
}

Result<OccupancyGrid> BuildStoreyGrid(const agraph::AGraph& graph,
                                      const geometry::TriangleMesh* mesh, const GridConfig& config,
                                      const std::vector<merging::WallDeviation>* deviations) {
  if (const std::string bad = config.Validate(); !bad.empty())
    return Result<OccupancyGrid>::Error("grid " + bad);
  if (graph.storeys.size() != 1)
    return Result<OccupancyGrid>::Error("the grid is built per storey: the A-Graph holds " +
                                        std::to_string(graph.storeys.size()) + " storeys");
  Eigen::AlignedBox2d box;
  for (const auto& r : graph.rooms)
    for (const auto& p : r.polygon) box.extend(p);
  for (const auto& w : graph.walls)
    for (const auto& p : WallFootprint(graph, w)) box.extend(p);
  if (box.isEmpty())
    return Result<OccupancyGrid>::Error("storey '" + graph.storeys[0].name +
                                        "' has no rooms or walls: no map");
  OccupancyGrid grid;
  grid.resolution = config.resolution;
  grid.elevation = graph.storeys[0].elevation;
  grid.origin = box.min() - Eigen::Vector2d::Constant(config.margin);
  const Eigen::Vector2d size = box.sizes() + Eigen::Vector2d::Constant(2.0 * config.margin);
  const double cells =
      std::ceil(size.x() / config.resolution) * std::ceil(size.y() / config.resolution);
  if (cells > 2e8)
    return Result<OccupancyGrid>::Error("storey '" + graph.storeys[0].name +
                                        "': " + std::to_string(static_cast<long>(cells)) +
                                        " cells at this resolution: too many");
  grid.width = static_cast<int>(std::ceil(size.x() / config.resolution));
  grid.height = static_cast<int>(std::ceil(size.y() / config.resolution));
  grid.cells.assign(static_cast<size_t>(grid.width) * grid.height, OccupancyGrid::kUnknown);

  GridRaster raster(grid);
  const double z0 = grid.elevation + config.slice_min, z1 = grid.elevation + config.slice_max;
  for (const auto& r : graph.rooms) raster.FillPolygon(r.polygon, OccupancyGrid::kFree);
  const std::vector<WallChange> changes = WallChanges(graph, deviations);
  std::set<long> changed_ifc_ids;
  for (const auto& w : graph.walls) {
    if (changes[w.id].removed || !changes[w.id].motion.matrix().isIdentity()) {
      raster.FillPolygon(WallFootprint(graph, w), OccupancyGrid::kFree);
      changed_ifc_ids.insert(w.ifc_id);
    }
  }
  if (mesh) DrawMesh(*mesh, z0, z1, changed_ifc_ids, raster);
  for (const auto& w : graph.walls)
    if (!changes[w.id].removed) DrawWall(graph, w, changes[w.id].motion, z0, z1, raster);
  for (const auto& d : graph.doorways) {
    if (!d.InWall()) continue;
    const double width = d.width > 0.0 ? d.width : config.door_default_width;
    const bool own_wall = d.wall >= 0 && d.wall < static_cast<int>(graph.walls.size());
    raster.FillPolygon(Moved(DoorwayPassage(graph, d, width),
                             own_wall ? changes[d.wall].motion : Eigen::Isometry2d::Identity()),
                       OccupancyGrid::kFree);
  }
  if (deviations) {
    for (const auto& d : *deviations) {
      if (d.status != merging::WallStatus::kExtra) continue;
      const Eigen::Vector2d along = d.end - d.start;
      if (along.norm() < 1e-6) continue;
      const Eigen::Vector2d n =
          0.5 * config.extra_thickness * Eigen::Vector2d(-along.y(), along.x()).normalized();
      raster.FillPolygon({d.start - n, d.end - n, d.end + n, d.start + n},
                         OccupancyGrid::kOccupied);
      raster.MarkSegment(d.start, d.end, OccupancyGrid::kOccupied);
    }
  }
  return Result<OccupancyGrid>::Ok(std::move(grid));
}

}  // namespace navigation
}  // namespace is_graphs
