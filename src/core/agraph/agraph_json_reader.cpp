#include <cmath>
#include <limits>

#include "agraph_json.h"
#include "is_graphs/agraph/agraph_io.h"
#include "is_graphs/agraph/agraph_validation.h"
#include "json_fields.h"

namespace is_graphs {
namespace agraph {
namespace internal {
namespace {

using nlohmann::json;

constexpr double kUnitNormalTolerance = 1e-3;

// Ids and references are ints in the structs; anything beyond is out of range anyway.
int ToInt(const JsonFields& fields, const char* key, long value) {
  if (value < std::numeric_limits<int>::min() || value > std::numeric_limits<int>::max()) {
    fields.Fail(std::string("'") + key + "' is out of range: " + std::to_string(value));
  }
  return static_cast<int>(value);
}

int Id(const JsonFields& fields, const char* key) {
  return ToInt(fields, key, fields.Integer(key));
}

// Opens element `index` of the array `name`, checking that its id equals its index.
JsonFields Element(const json& array, const char* name, size_t index, const char* ifc_class,
                   long* ifc_id) {
  const json& object = array[index];
  *ifc_id = -1;
  if (object.is_object() && object.contains("ifc_id") && object["ifc_id"].is_number_integer()) {
    *ifc_id = object["ifc_id"].get<long>();
  }
  JsonFields fields(object, ElementLabel(name, static_cast<int>(index), ifc_class, *ifc_id));
  fields.IntegerOr("ifc_id", -1);  // type check
  const long id = fields.Integer("id");
  if (id != static_cast<long>(index)) {
    fields.Fail("id " + std::to_string(id) + " differs from its index " + std::to_string(index) +
                " (ids must be dense indices)");
  }
  return fields;
}

geometry::Plane ReadPlane(const JsonFields& fields) {
  const Eigen::Vector3d normal = fields.Vector3("normal");
  const double norm = normal.norm();
  if (std::abs(norm - 1.0) > kUnitNormalTolerance) {
    fields.Fail("normal is not a unit vector (|n| = " + std::to_string(norm) + ")");
  }
  return geometry::Plane(normal, fields.Number("d"));  // renormalizes
}

void ReadSurface(const JsonFields& f, WallSurface* s) {
  s->guid = f.StringOr("guid", "");
  s->wall = Id(f, "wall");
  s->storey = Id(f, "storey");
  s->plane = ReadPlane(f);
  if (f.Has("orientation")) {
    const auto orientation = geometry::OrientationFromString(f.String("orientation"));
    if (!orientation) f.Fail("orientation must be \"x\", \"y\" or \"other\"");
    s->orientation = *orientation;
  } else {
    s->orientation = geometry::ClassifyOrientation(s->plane.normal);
  }
  s->start = f.Vector2("start");
  s->end = f.Vector2("end");
  s->z_min = f.Number("z_min");
  s->z_max = f.Number("z_max");
  s->rooms = f.IndicesOr("rooms");
}

void ReadWall(const JsonFields& f, Wall* w) {
  w->guid = f.StringOr("guid", "");
  w->name = f.StringOr("name", "");
  w->storey = Id(f, "storey");
  const std::vector<int> surfaces = f.Indices("surfaces");
  if (surfaces.size() != 2) {
    f.Fail("surfaces must hold two wall_surfaces ids, got " + std::to_string(surfaces.size()));
  }
  w->surface_a = surfaces[0];
  w->surface_b = surfaces[1];
  w->thickness = f.NumberOr("thickness", 0.0);
  w->start = f.Vector3("start");
  w->center = f.Vector3("center");
  w->length = f.NumberOr("length", 0.0);
  w->height = f.NumberOr("height", 0.0);
  w->external = f.BoolOr("external", false);
}

void ReadRoom(const JsonFields& f, Room* r) {
  r->guid = f.StringOr("guid", "");
  r->name = f.StringOr("name", "");
  r->long_name = f.StringOr("long_name", "");
  r->storey = Id(f, "storey");
  r->polygon = f.Points2("polygon");
  if (r->polygon.size() < 3) {
    f.Fail("polygon has " + std::to_string(r->polygon.size()) + " vertices, needs at least 3");
  }
  r->z_min = f.Number("z_min");
  r->z_max = f.Number("z_max");
  // Files of converter 6 and older have no floor_z: the storey's elevation, set once the
  // storeys are read (FillMissingFloors).
  r->floor_z = f.NumberOr("floor_z", std::numeric_limits<double>::quiet_NaN());
  r->floor_source = f.StringOr("floor_source", "");
  r->center = f.Vector3("center");
  r->area = f.NumberOr("area", 0.0);
  r->surfaces = f.IndicesOr("surfaces");
  r->walls = f.IndicesOr("walls");
  r->doorways = f.IndicesOr("doorways");
}

void ReadDoorway(const JsonFields& f, Doorway* d) {
  const std::string kind = f.StringOr("kind", "door");  // version-1 files: doors only
  if (kind == "door") {
    d->kind = DoorwayKind::kDoor;
  } else if (kind == "opening") {
    d->kind = DoorwayKind::kOpening;
  } else if (kind == "virtual") {
    d->kind = DoorwayKind::kVirtual;
  } else {
    f.Fail("kind must be door, opening or virtual, got '" + kind + "'");
  }
  d->guid = f.StringOr("guid", "");
  d->name = f.StringOr("name", "");
  d->storey = Id(f, "storey");
  d->wall = ToInt(f, "wall", f.IntegerOr("wall", -1));
  d->position = f.Vector3("position");
  d->width = f.NumberOr("width", 0.0);
  d->height = f.NumberOr("height", 0.0);
  d->rooms = f.Indices("rooms");
  if (d->rooms.size() != 1 && d->rooms.size() != 2) {
    f.Fail("rooms must hold one or two room ids, got " + std::to_string(d->rooms.size()));
  }
}

void ReadStorey(const JsonFields& f, Storey* s) {
  s->guid = f.StringOr("guid", "");
  s->name = f.StringOr("name", "");
  s->elevation = f.NumberOr("elevation", 0.0);
  s->height = f.NumberOr("height", 0.0);
}

// Reads the array `name` of `root` into `out` with `read` for each element.
template <typename Element_t, typename ReadFn>
void ReadArray(const JsonFields& root, const char* name, const char* ifc_class, ReadFn read,
               std::vector<Element_t>* out) {
  const json& array = root.Array(name);
  out->resize(array.size());
  for (size_t i = 0; i < array.size(); ++i) {
    long ifc_id = -1;
    const JsonFields fields = Element(array, name, i, ifc_class, &ifc_id);
    Element_t& element = (*out)[i];
    element.id = static_cast<int>(i);
    element.ifc_id = ifc_id;
    read(fields, &element);
  }
}

// A room without floor_z (a file of converter 6 or older) stands on its storey's elevation, the
// height every room of a storey had before; floor_source stays "".
void FillMissingFloors(AGraph* graph) {
  for (Room& r : graph->rooms) {
    if (!std::isnan(r.floor_z)) continue;
    const bool known = r.storey >= 0 && r.storey < static_cast<int>(graph->storeys.size());
    r.floor_z = known ? graph->storeys[r.storey].elevation : r.z_min;
    r.floor_source.clear();
  }
}

}  // namespace

void AGraphFromJson(const json& root_json, AGraph* graph) {
  const JsonFields root(root_json, "top level");
  const std::string format = root.String("format");
  if (format != kAGraphFormatName) {
    root.Fail("format is \"" + format + "\", expected \"" + kAGraphFormatName + "\"");
  }
  const long version = root.Integer("version");
  if (version > kAGraphFormatVersion) {
    root.Fail("format version " + std::to_string(version) + " is newer than this reader (" +
              std::to_string(kAGraphFormatVersion) + "): update is_graphs");
  }
  if (version < 1) root.Fail("format version " + std::to_string(version) + " is invalid");
  graph->format_version = static_cast<int>(version);

  if (root.Has("source")) {
    const JsonFields source(root_json["source"], "source");
    graph->source.file = source.StringOr("file", "");
    graph->source.sha256 = source.StringOr("sha256", "");
    graph->source.schema = source.StringOr("schema", "");
    graph->source.application = source.StringOr("application", "");
    graph->source.length_unit_m = source.NumberOr("length_unit_m", 1.0);
    graph->source.converter_version = source.StringOr("converter_version", "");
  }
  graph->building = root.StringOr("building", "");
  graph->mesh = root.StringOr("mesh", "");
  graph->warnings = root.StringsOr("warnings");
  if (root.Has("report")) {
    const json& report = root.Array("report");
    for (size_t i = 0; i < report.size(); ++i) {
      const JsonFields entry(report[i], "report[" + std::to_string(i) + "]");
      const int storey = static_cast<int>(entry.Integer("storey"));
      if (!entry.Has("dropped")) continue;
      const json& dropped = entry.Array("dropped");
      for (size_t k = 0; k < dropped.size(); ++k) {
        const JsonFields d(dropped[k], entry.label() + ".dropped[" + std::to_string(k) + "]");
        graph->dropped.push_back({storey, d.StringOr("ifc_class", ""), d.StringOr("reason", ""),
                                  static_cast<int>(d.IntegerOr("count", 1))});
      }
    }
  }

  ReadArray(root, "storeys", "IfcBuildingStorey", ReadStorey, &graph->storeys);
  ReadArray(root, "wall_surfaces", "IfcWall", ReadSurface, &graph->surfaces);
  ReadArray(root, "walls", "IfcWall", ReadWall, &graph->walls);
  ReadArray(root, "rooms", "IfcSpace", ReadRoom, &graph->rooms);
  ReadArray(root, "doorways", "IfcDoor", ReadDoorway, &graph->doorways);
  FillMissingFloors(graph);
}

}  // namespace internal
}  // namespace agraph
}  // namespace is_graphs
