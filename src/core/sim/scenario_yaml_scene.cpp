// The `scene` section of a scenario YAML: mesh classes to drop, BIM deviations, clutter, glass,
// the world outside, people who walk and doors that swing.
#include "yaml_fields.h"

namespace is_graphs {
namespace sim {
namespace yaml_fields {
namespace {

const std::set<std::string> kClutterTypes{"box",    "cylinder", "pallet",
                                          "person", "column",   "scaffolding"};

WallRef ParseWallRef(const YAML::Node& n, const std::string& f) {
  WallRef ref;
  if (!n) Fail(f, "missing (a wall name or A-Graph wall id)");
  int id = -1;
  if (YAML::convert<int>::decode(n, id)) {
    ref.id = id;
  } else {
    ref.name = As<std::string>(n, f, "a wall name or an A-Graph wall id");
  }
  return ref;
}

DeviationConfig ParseDeviation(const YAML::Node& n, const std::string& f) {
  CheckMap(
      n, f,
      {"type", "wall", "doorway", "offset", "angle_deg", "start", "end", "thickness", "height"});
  DeviationConfig d;
  std::string type;
  Get(n, f, "type", &type);
  if (type == "move_wall") {
    d.type = DeviationConfig::Type::kMoveWall;
    d.wall = ParseWallRef(n["wall"], f + ".wall");
    if (!n["offset"]) Fail(f + ".offset", "missing (metres along the wall normal)");
    Get(n, f, "offset", &d.offset);
  } else if (type == "rotate_wall") {
    d.type = DeviationConfig::Type::kRotateWall;
    d.wall = ParseWallRef(n["wall"], f + ".wall");
    if (!n["angle_deg"]) Fail(f + ".angle_deg", "missing (degrees about the wall's centre)");
    Get(n, f, "angle_deg", &d.angle_deg);
  } else if (type == "remove_wall") {
    d.type = DeviationConfig::Type::kRemoveWall;
    d.wall = ParseWallRef(n["wall"], f + ".wall");
  } else if (type == "add_wall") {
    d.type = DeviationConfig::Type::kAddWall;
    if (!n["start"] || !n["end"]) Fail(f, "add_wall needs `start` and `end` ([x, y])");
    d.start = Vec2(n["start"], f + ".start");
    d.end = Vec2(n["end"], f + ".end");
    Get(n, f, "thickness", &d.thickness);
    Get(n, f, "height", &d.height);
  } else if (type == "close_doorway") {
    d.type = DeviationConfig::Type::kCloseDoorway;
    if (!n["doorway"]) Fail(f + ".doorway", "missing (a doorway name or A-Graph doorway id)");
    d.doorway = ParseWallRef(n["doorway"], f + ".doorway");
    Get(n, f, "height", &d.height);
  } else {
    Fail(f + ".type",
         "must be move_wall, rotate_wall, remove_wall, add_wall or close_doorway, got '" + type +
             "'");
  }
  return d;
}

ClutterConfig ParseClutter(const YAML::Node& n, const std::string& f) {
  CheckMap(n, f,
           {"type", "position", "room", "offset", "size", "radius", "height", "yaw_deg",
            "reflectivity"});
  ClutterConfig c;
  Get(n, f, "type", &c.type);
  if (!kClutterTypes.count(c.type)) {
    Fail(f + ".type",
         "must be box, cylinder, pallet, person, column or scaffolding, got '" + c.type + "'");
  }
  if (n["position"]) c.position = Vec2(n["position"], f + ".position");
  Get(n, f, "room", &c.room);
  if (n["offset"]) c.offset = Vec2(n["offset"], f + ".offset");
  if (n["size"]) c.size = Vec3(n["size"], f + ".size");
  Get(n, f, "radius", &c.radius);
  Get(n, f, "height", &c.height);
  Get(n, f, "yaw_deg", &c.yaw_deg);
  Get(n, f, "reflectivity", &c.reflectivity);
  return c;
}

OutsideObjectConfig ParseOutside(const YAML::Node& n, const std::string& f) {
  CheckMap(n, f,
           {"type", "position", "size", "radius", "height", "yaw_deg", "reflectivity", "base_z"});
  OutsideObjectConfig o;
  Get(n, f, "type", &o.type);
  if (o.type != "building" && o.type != "car" && o.type != "tree" && o.type != "wall")
    Fail(f + ".type", "must be building, car, tree or wall, got '" + o.type + "'");
  if (!n["position"]) Fail(f + ".position", "missing ([x, y] in bim, outside the building)");
  o.position = Vec2(n["position"], f + ".position");
  if (n["size"]) o.size = Vec3(n["size"], f + ".size");
  Get(n, f, "radius", &o.radius);
  Get(n, f, "height", &o.height);
  Get(n, f, "yaw_deg", &o.yaw_deg);
  Get(n, f, "reflectivity", &o.reflectivity);
  if (n["base_z"]) {
    double z = 0.0;
    Get(n, f, "base_z", &z);
    o.base_z = z;
  }
  return o;
}

MoverConfig ParseMover(const YAML::Node& n, const std::string& f) {
  CheckMap(n, f, {"type", "rooms", "waypoints", "speed", "start", "reflectivity"});
  MoverConfig m;
  Get(n, f, "type", &m.type);
  if (n["rooms"]) m.rooms = Strings(n["rooms"], f + ".rooms");
  if (n["waypoints"]) {
    if (!n["waypoints"].IsSequence()) Fail(f + ".waypoints", "must be a list of [x, y]");
    for (std::size_t i = 0; i < n["waypoints"].size(); ++i)
      m.waypoints.push_back(Vec2(n["waypoints"][i], f + ".waypoints[" + std::to_string(i) + "]"));
  }
  Get(n, f, "speed", &m.speed);
  Get(n, f, "start", &m.start);
  Get(n, f, "reflectivity", &m.reflectivity);
  return m;
}

SwingingDoorConfig ParseDoor(const YAML::Node& n, const std::string& f) {
  CheckMap(n, f, {"between", "doorway", "period", "phase", "open_deg", "hold_distance"});
  SwingingDoorConfig d;
  if (n["between"]) d.between = Strings(n["between"], f + ".between");
  Get(n, f, "doorway", &d.doorway);
  Get(n, f, "period", &d.period);
  Get(n, f, "phase", &d.phase);
  Get(n, f, "open_deg", &d.open_deg);
  Get(n, f, "hold_distance", &d.hold_distance);
  return d;
}

}  // namespace

void ParseScene(const YAML::Node& n, SceneConfig* s) {
  const std::string f = "scene";
  CheckMap(n, f,
           {"drop_classes", "deviations", "clutter", "random_clutter", "wall_reflectivity",
            "floor_reflectivity", "glass", "outside", "polished_floor", "people", "doors"});
  if (n["drop_classes"]) s->drop_classes = Strings(n["drop_classes"], f + ".drop_classes");
  for (const char* list : {"deviations", "clutter", "outside", "people", "doors"}) {
    if (n[list] && !n[list].IsSequence()) Fail(Join(f, list), "must be a list");
  }
  for (std::size_t i = 0; n["deviations"] && i < n["deviations"].size(); ++i) {
    s->deviations.push_back(
        ParseDeviation(n["deviations"][i], f + ".deviations[" + std::to_string(i) + "]"));
  }
  for (std::size_t i = 0; n["clutter"] && i < n["clutter"].size(); ++i) {
    s->clutter.push_back(ParseClutter(n["clutter"][i], f + ".clutter[" + std::to_string(i) + "]"));
  }
  for (std::size_t i = 0; n["outside"] && i < n["outside"].size(); ++i) {
    s->outside.push_back(ParseOutside(n["outside"][i], f + ".outside[" + std::to_string(i) + "]"));
  }
  for (std::size_t i = 0; n["people"] && i < n["people"].size(); ++i)
    s->people.push_back(ParseMover(n["people"][i], f + ".people[" + std::to_string(i) + "]"));
  for (std::size_t i = 0; n["doors"] && i < n["doors"].size(); ++i)
    s->doors.push_back(ParseDoor(n["doors"][i], f + ".doors[" + std::to_string(i) + "]"));
  if (n["random_clutter"]) {
    const YAML::Node r = n["random_clutter"];
    const std::string rf = f + ".random_clutter";
    CheckMap(r, rf, {"count", "types", "rooms", "wall_margin"});
    Get(r, rf, "count", &s->random_clutter.count);
    if (r["types"]) s->random_clutter.types = Strings(r["types"], rf + ".types");
    if (s->random_clutter.types.empty()) Fail(rf + ".types", "must not be empty");
    for (std::size_t i = 0; i < s->random_clutter.types.size(); ++i) {
      if (!kClutterTypes.count(s->random_clutter.types[i])) {
        Fail(rf + ".types[" + std::to_string(i) + "]",
             "must be box, cylinder, pallet, person, column or scaffolding");
      }
    }
    if (r["rooms"]) s->random_clutter.rooms = Strings(r["rooms"], rf + ".rooms");
    Get(r, rf, "wall_margin", &s->random_clutter.wall_margin);
  }
  Get(n, f, "wall_reflectivity", &s->wall_reflectivity);
  Get(n, f, "floor_reflectivity", &s->floor_reflectivity);
  Get(n, f, "polished_floor", &s->polished_floor);
  if (n["glass"]) {  // present (even `glass: {}`): on, with the defaults for what is not given
    const YAML::Node g = n["glass"];
    const std::string gf = f + ".glass";
    if (!g.IsMap()) Fail(gf, "must be a map (classes, return_probability, ...), {} for defaults");
    CheckMap(g, gf, {"classes", "return_probability", "return_max_angle_deg", "max_layers"});
    s->glass.enabled = true;
    if (g["classes"]) s->glass.classes = Strings(g["classes"], gf + ".classes");
    Get(g, gf, "return_probability", &s->glass.return_probability);
    Get(g, gf, "return_max_angle_deg", &s->glass.return_max_angle_deg);
    Get(g, gf, "max_layers", &s->glass.max_layers);
  }
}

}  // namespace yaml_fields
}  // namespace sim
}  // namespace is_graphs
