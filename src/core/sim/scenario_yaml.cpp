#include "is_graphs/sim/scenario_yaml.h"

#include <yaml-cpp/yaml.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "yaml_fields.h"

namespace is_graphs {
namespace sim {
namespace {

using namespace yaml_fields;  // NOLINT(build/namespaces): this file's own helpers

// The route keys shared by `trajectory` and `kidnap`: rooms, waypoints, start.
void ParseRoute(const YAML::Node& n, const std::string& f, std::vector<std::string>* rooms,
                std::vector<WaypointConfig>* waypoints, StartConfig* start) {
  if (n["rooms"]) *rooms = Strings(n["rooms"], f + ".rooms");
  if (n["waypoints"]) {
    if (!n["waypoints"].IsSequence()) Fail(f + ".waypoints", "must be a list of [x, y(, yaw)]");
    for (std::size_t i = 0; i < n["waypoints"].size(); ++i) {
      const std::vector<double> v =
          Numbers(n["waypoints"][i], f + ".waypoints[" + std::to_string(i) + "]", 2, 3);
      WaypointConfig w;
      w.position = {v[0], v[1]};
      if (v.size() == 3) w.yaw = v[2];
      waypoints->push_back(w);
    }
  }
  if (n["start"]) {
    CheckMap(n["start"], f + ".start", {"room", "pose"});
    Get(n["start"], f + ".start", "room", &start->room);
    if (n["start"]["pose"]) start->pose = Vec3(n["start"]["pose"], f + ".start.pose");
  }
}

void ParseTrajectory(const YAML::Node& n, TrajectoryConfig* t) {
  const std::string f = "trajectory";
  CheckMap(n, f,
           {"rooms", "waypoints", "start", "speed", "acceleration", "turn_rate_deg",
            "turn_acceleration_deg", "pause", "doorway_clearance", "loop", "follow_terrain",
            "stairs_speed"});
  ParseRoute(n, f, &t->rooms, &t->waypoints, &t->start);
  Get(n, f, "speed", &t->speed);
  Get(n, f, "acceleration", &t->acceleration);
  Get(n, f, "turn_rate_deg", &t->turn_rate_deg);
  Get(n, f, "turn_acceleration_deg", &t->turn_acceleration_deg);
  Get(n, f, "pause", &t->pause);
  Get(n, f, "doorway_clearance", &t->doorway_clearance);
  Get(n, f, "loop", &t->loop);
  Get(n, f, "follow_terrain", &t->follow_terrain);
  Get(n, f, "stairs_speed", &t->stairs_speed);
}

KidnapConfig ParseKidnap(const YAML::Node& n) {
  const std::string f = "kidnap";
  CheckMap(n, f, {"time", "rooms", "waypoints", "start", "loop"});
  KidnapConfig k;
  if (!n["time"]) Fail(f + ".time", "missing (s after the start when the robot is carried)");
  Get(n, f, "time", &k.time);
  ParseRoute(n, f, &k.rooms, &k.waypoints, &k.start);
  Get(n, f, "loop", &k.loop);
  return k;
}

// `model` first: its data-sheet defaults, then the other keys over them.
void ParseSensor(const YAML::Node& n, LidarConfig* s) {
  const std::string f = "sensor";
  CheckMap(n, f,
           {"model", "rotation_rate_hz", "azimuth_resolution_deg", "min_range", "max_range",
            "range_noise_stddev", "range_resolution", "max_incidence_deg", "dropout_probability",
            "intensity_noise_stddev", "azimuth_offset_deg", "dropouts", "effects"});
  if (n["model"]) {
    const std::string name = As<std::string>(n["model"], f + ".model", "a string");
    const auto model = ParseLidarModel(name);
    if (!model)
      Fail(f + ".model", "unknown model '" + name + "' (expected vlp16, os1_64 or hesai_xt32)");
    *s = LidarConfig::For(*model);
  }
  Get(n, f, "rotation_rate_hz", &s->rotation_rate_hz);
  Get(n, f, "azimuth_resolution_deg", &s->azimuth_resolution_deg);
  Get(n, f, "min_range", &s->min_range);
  Get(n, f, "max_range", &s->max_range);
  Get(n, f, "range_noise_stddev", &s->range_noise_stddev);
  Get(n, f, "range_resolution", &s->range_resolution);
  Get(n, f, "max_incidence_deg", &s->max_incidence_deg);
  Get(n, f, "dropout_probability", &s->dropout_probability);
  Get(n, f, "intensity_noise_stddev", &s->intensity_noise_stddev);
  Get(n, f, "azimuth_offset_deg", &s->azimuth_offset_deg);
  if (n["dropouts"]) {
    const YAML::Node& d = n["dropouts"];
    if (!d.IsSequence()) Fail(f + ".dropouts", "must be a list of [t_start, t_end]");
    for (std::size_t i = 0; i < d.size(); ++i) {
      const std::vector<double> v = Numbers(d[i], f + ".dropouts[" + std::to_string(i) + "]", 2, 2);
      s->dropouts.push_back({v[0], v[1]});
    }
  }
  if (n["effects"]) ParseSensorEffects(n["effects"], &s->effects);
}

void ParseGait(const YAML::Node& n, GaitConfig* g) {
  const std::string f = "gait";
  CheckMap(n, f,
           {"step_frequency_hz", "bob_amplitude", "roll_amplitude_deg", "pitch_amplitude_deg",
            "full_activity_speed", "standing_height"});
  Get(n, f, "step_frequency_hz", &g->step_frequency_hz);
  Get(n, f, "bob_amplitude", &g->bob_amplitude);
  Get(n, f, "roll_amplitude_deg", &g->roll_amplitude_deg);
  Get(n, f, "pitch_amplitude_deg", &g->pitch_amplitude_deg);
  Get(n, f, "full_activity_speed", &g->full_activity_speed);
  Get(n, f, "standing_height", &g->standing_height);
}

void ParseOdometry(const YAML::Node& n, OdometryConfig* o) {
  const std::string f = "odometry";
  CheckMap(n, f,
           {"rate_hz", "scale_error", "yaw_bias_per_m", "yaw_bias_per_s", "translation_random_walk",
            "yaw_random_walk", "z_scale_error"});
  Get(n, f, "rate_hz", &o->rate_hz);
  Get(n, f, "scale_error", &o->scale_error);
  Get(n, f, "yaw_bias_per_m", &o->yaw_bias_per_m);
  Get(n, f, "yaw_bias_per_s", &o->yaw_bias_per_s);
  Get(n, f, "translation_random_walk", &o->translation_random_walk);
  Get(n, f, "yaw_random_walk", &o->yaw_random_walk);
  Get(n, f, "z_scale_error", &o->z_scale_error);
}

ScenarioConfig ParseRoot(const YAML::Node& root) {
  CheckMap(root, "",
           {"name", "description", "building", "storey", "localizer_storey", "seed", "duration",
            "start_time", "trajectory", "kidnap", "sensor", "gait", "odometry", "scene"});
  ScenarioConfig c;
  Get(root, "", "name", &c.name);
  if (!root["building"]) Fail("building", "missing (path of an .ifc or .agraph.json file)");
  Get(root, "", "building", &c.building);
  Get(root, "", "storey", &c.storey);
  if (root["localizer_storey"]) {
    std::string s;
    Get(root, "", "localizer_storey", &s);
    c.localizer_storey = s;
  }
  if (root["seed"]) {
    c.seed = As<std::uint64_t>(root["seed"], "seed", "a non-negative integer");
  }
  Get(root, "", "duration", &c.duration);
  Get(root, "", "start_time", &c.start_time);
  if (!root["trajectory"]) Fail("trajectory", "missing");
  ParseTrajectory(root["trajectory"], &c.trajectory);
  if (root["kidnap"]) c.kidnap = ParseKidnap(root["kidnap"]);
  if (root["sensor"]) ParseSensor(root["sensor"], &c.sensor);
  if (root["gait"]) ParseGait(root["gait"], &c.gait);
  if (root["odometry"]) ParseOdometry(root["odometry"], &c.odometry);
  if (root["scene"]) ParseScene(root["scene"], &c.scene);
  return c;
}

}  // namespace

std::string WithYamlLine(const std::string& text, const std::string& name,
                         const std::string& error) {
  // The field path: the error's text up to the first ':' or ' ', as "a.b[2].c".
  const std::size_t end = error.find_first_of(": ");
  const std::string path = error.substr(0, end);
  int line = -1;
  try {
    YAML::Node node = YAML::Load(text);
    std::size_t i = 0;
    while (i < path.size() && node.IsDefined()) {
      std::size_t j = path.find_first_of(".[", i);
      const std::string key = path.substr(i, j == std::string::npos ? std::string::npos : j - i);
      if (!key.empty()) {
        if (!node.IsMap()) break;
        const YAML::Node child = static_cast<const YAML::Node&>(node)[key];  // no key made
        if (!child) break;
        node.reset(child);  // (operator= would overwrite the tree)
        line = node.Mark().line;
      }
      i = j == std::string::npos ? path.size() : j;
      while (i < path.size() && path[i] == '[') {  // [index]s
        const std::size_t close = path.find(']', i);
        if (close == std::string::npos) break;
        const int index = std::atoi(path.substr(i + 1, close - i - 1).c_str());
        if (!node.IsSequence() || index < 0 || index >= static_cast<int>(node.size())) {
          i = path.size();
          break;
        }
        node.reset(static_cast<const YAML::Node&>(node)[index]);
        line = node.Mark().line;
        i = close + 1;
      }
      if (i < path.size() && path[i] == '.') ++i;
    }
  } catch (const YAML::Exception&) {
    line = -1;
  }
  if (line < 0 || path.find_first_of("abcdefghijklmnopqrstuvwxyz") == std::string::npos)
    return name + ": " + error;
  return name + ":" + std::to_string(line + 1) + ": " + error;
}

Result<ScenarioConfig> ParseScenarioYaml(const std::string& text, const std::string& name,
                                         const std::string& base_dir) {
  try {
    const YAML::Node root = YAML::Load(text);
    ScenarioConfig config = ParseRoot(root);
    config.base_dir = base_dir;
    const std::string error = config.Validate();
    if (!error.empty()) return Result<ScenarioConfig>::Error(WithYamlLine(text, name, error));
    return Result<ScenarioConfig>::Ok(std::move(config));
  } catch (const FieldError& e) {
    return Result<ScenarioConfig>::Error(WithYamlLine(text, name, e.what()));
  } catch (const YAML::Exception& e) {
    std::ostringstream out;
    out << name << ":" << e.mark.line + 1 << ":" << e.mark.column + 1
        << ": invalid YAML: " << e.msg;
    return Result<ScenarioConfig>::Error(out.str());
  }
}

Result<ScenarioConfig> LoadScenarioYaml(const std::string& path, const std::string& base_dir) {
  std::ifstream in(path);
  if (!in) return Result<ScenarioConfig>::Error(path + ": cannot open the scenario file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return ParseScenarioYaml(buffer.str(), path, base_dir);
}

}  // namespace sim
}  // namespace is_graphs
