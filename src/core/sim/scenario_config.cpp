#include "is_graphs/sim/scenario_config.h"

#include <cmath>
#include <sstream>

namespace is_graphs {
namespace sim {
namespace {

// "field: must be <what>, got <value>" when !(lo <= value <= hi) (NaN fails).
std::string Range(const std::string& field, double value, double lo, double hi,
                  const std::string& unit = "") {
  if (value >= lo && value <= hi) return "";
  std::ostringstream out;
  out << field << ": must be in [" << lo << ", " << hi << "]" << (unit.empty() ? "" : " ") << unit
      << ", got " << value;
  return out.str();
}

// As Range with an open lower bound: lo < value <= hi.
std::string Positive(const std::string& field, double value, double hi,
                     const std::string& unit = "") {
  if (value > 0.0 && value <= hi) return "";
  std::ostringstream out;
  out << field << ": must be > 0 and <= " << hi << (unit.empty() ? "" : " ") << unit << ", got "
      << value;
  return out.str();
}

std::string First(std::initializer_list<std::string> errors) {
  for (const std::string& e : errors) {
    if (!e.empty()) return e;
  }
  return "";
}

// "sensor.dropouts[i]: ..." for the first window that is not 0 <= start < end <= 3600 or
// starts before the previous one ends.
std::string Dropouts(const std::vector<TimeWindow>& dropouts) {
  for (std::size_t i = 0; i < dropouts.size(); ++i) {
    const TimeWindow& w = dropouts[i];
    std::ostringstream out;
    out << "sensor.dropouts[" << i << "]: ";
    if (!(w.start >= 0.0 && w.start < w.end && w.end <= 3600.0)) {
      out << "must be [t_start, t_end] in s with 0 <= t_start < t_end <= 3600, got [" << w.start
          << ", " << w.end << "]";
      return out.str();
    }
    if (i > 0 && w.start < dropouts[i - 1].end) {
      out << "must start after sensor.dropouts[" << i - 1 << "] ends (" << dropouts[i - 1].end
          << " s), got " << w.start;
      return out.str();
    }
  }
  return "";
}

// The route fields shared by `trajectory` and `kidnap`.
std::string RouteChoice(const std::string& f, const std::vector<std::string>& rooms,
                        const std::vector<WaypointConfig>& waypoints, const StartConfig& start) {
  if (rooms.empty() && waypoints.empty()) {
    return f + ": needs `rooms` (room names to visit) or `waypoints`";
  }
  if (!rooms.empty() && !waypoints.empty()) {
    return f + ": give either `rooms` or `waypoints`, not both";
  }
  if (!start.room.empty() && start.pose) {
    return f + ".start: give either `room` or `pose`, not both";
  }
  return "";
}

}  // namespace

const char* ToString(LidarModelKind model) {
  switch (model) {
    case LidarModelKind::kVlp16:
      return "vlp16";
    case LidarModelKind::kOs1_64:
      return "os1_64";
    case LidarModelKind::kHesaiXt32:
      return "hesai_xt32";
  }
  return "?";
}

std::optional<LidarModelKind> ParseLidarModel(const std::string& name) {
  for (auto m : {LidarModelKind::kVlp16, LidarModelKind::kOs1_64, LidarModelKind::kHesaiXt32})
    if (name == ToString(m)) return m;
  return std::nullopt;
}

LidarConfig LidarConfig::For(LidarModelKind model) {
  LidarConfig c;
  c.model = model;
  switch (model) {
    case LidarModelKind::kVlp16:
      break;
    case LidarModelKind::kOs1_64:
      // OS1 data sheet (rev 6/7): 0.5 m minimum range, 1 cm range precision (1σ) at indoor
      // ranges, 1 mm range resolution; ouster-ros' intensity is signal photons (0..1000 here).
      c.azimuth_resolution_deg = 360.0 / 1024.0;
      c.min_range = 0.5;
      c.max_range = 120.0;
      c.range_noise_stddev = 0.01;
      c.range_resolution = 0.001;
      c.intensity_noise_stddev = 20.0;
      break;
    case LidarModelKind::kHesaiXt32:
      // PandarXT-32 data sheet: 0.05-120 m, accuracy ±1 cm (precision 0.5 cm 1σ), 4 mm distance
      // unit, 0.18° horizontal resolution at 10 Hz; intensity 0..255.
      c.azimuth_resolution_deg = 0.18;
      c.min_range = 0.05;
      c.max_range = 120.0;
      c.range_noise_stddev = 0.01;
      c.range_resolution = 0.004;
      c.intensity_noise_stddev = 5.0;
      break;
  }
  return c;
}

std::string LidarConfig::Validate() const {
  if (model == LidarModelKind::kOs1_64) {
    const long columns = std::lround(360.0 / azimuth_resolution_deg);
    if (columns != 512 && columns != 1024 && columns != 2048)
      return "sensor.azimuth_resolution_deg: an OS1 runs 512, 1024 or 2048 columns per turn "
             "(0.703125, 0.3515625 or 0.17578125 deg), got " +
             std::to_string(azimuth_resolution_deg);
  }
  return First({Positive("sensor.rotation_rate_hz", rotation_rate_hz, 20.0, "Hz"),
                Positive("sensor.azimuth_resolution_deg", azimuth_resolution_deg, 10.0, "deg"),
                Range("sensor.min_range", min_range, 0.0, 10.0, "m"),
                Positive("sensor.max_range", max_range, 1000.0, "m"),
                max_range > min_range ? "" : "sensor.max_range: must exceed sensor.min_range",
                Range("sensor.range_noise_stddev", range_noise_stddev, 0.0, 1.0, "m"),
                Range("sensor.range_resolution", range_resolution, 0.0, 0.1, "m"),
                Range("sensor.max_incidence_deg", max_incidence_deg, 0.0, 90.0, "deg"),
                Range("sensor.dropout_probability", dropout_probability, 0.0, 1.0),
                Range("sensor.intensity_noise_stddev", intensity_noise_stddev, 0.0, 100.0),
                Range("sensor.azimuth_offset_deg", azimuth_offset_deg, -360.0, 360.0, "deg"),
                Dropouts(dropouts), effects.Validate()});
}

std::string GaitConfig::Validate() const {
  return First({Positive("gait.step_frequency_hz", step_frequency_hz, 10.0, "Hz"),
                Range("gait.bob_amplitude", bob_amplitude, 0.0, 0.2, "m"),
                Range("gait.roll_amplitude_deg", roll_amplitude_deg, 0.0, 20.0, "deg"),
                Range("gait.pitch_amplitude_deg", pitch_amplitude_deg, 0.0, 20.0, "deg"),
                Positive("gait.full_activity_speed", full_activity_speed, 5.0, "m/s"),
                Positive("gait.standing_height", standing_height, 2.0, "m")});
}

std::string TrajectoryConfig::Validate() const {
  return First(
      {RouteChoice("trajectory", rooms, waypoints, start),
       Range("trajectory.speed", speed, 0.3, 1.2, "m/s"),
       Positive("trajectory.acceleration", acceleration, 10.0, "m/s^2"),
       Positive("trajectory.turn_rate_deg", turn_rate_deg, 360.0, "deg/s"),
       Positive("trajectory.turn_acceleration_deg", turn_acceleration_deg, 3600.0, "deg/s^2"),
       Range("trajectory.pause", pause, 0.0, 600.0, "s"),
       Range("trajectory.doorway_clearance", doorway_clearance, 0.3, 5.0, "m"),
       Range("trajectory.stairs_speed", stairs_speed, 0.1, 1.2, "m/s")});
}

std::string KidnapConfig::Validate() const {
  if (!(time > 0.0 && time <= 3600.0)) {
    std::ostringstream out;
    out << "kidnap.time: must be > 0 and <= 3600 s, got " << time;
    return out.str();
  }
  return RouteChoice("kidnap", rooms, waypoints, start);
}

TrajectoryConfig KidnapConfig::AsTrajectory(const TrajectoryConfig& base) const {
  TrajectoryConfig t = base;
  t.rooms = rooms;
  t.waypoints = waypoints;
  t.start = start;
  t.loop = loop;
  return t;
}

std::string OdometryConfig::Validate() const {
  return First(
      {Positive("odometry.rate_hz", rate_hz, 1000.0, "Hz"),
       Range("odometry.scale_error", scale_error, -0.5, 0.5),
       Range("odometry.yaw_bias_per_m", yaw_bias_per_m, -1.0, 1.0, "rad/m"),
       Range("odometry.yaw_bias_per_s", yaw_bias_per_s, -1.0, 1.0, "rad/s"),
       Range("odometry.translation_random_walk", translation_random_walk, 0.0, 1.0, "m/sqrt(m)"),
       Range("odometry.yaw_random_walk", yaw_random_walk, 0.0, 1.0, "rad/sqrt(m)"),
       Range("odometry.z_scale_error", z_scale_error, -0.2, 0.2)});
}

std::string ScenarioConfig::Validate() const {
  if (building.empty()) return "building: missing (path of an .ifc or .agraph.json file)";
  if (!(duration >= 0.0 && duration <= 3600.0)) {
    return "duration: must be in [0, 3600] s, got " + std::to_string(duration);
  }
  if (!(start_time > 0.0 && start_time < 4.0e9)) {
    return "start_time: must be a positive ROS time in seconds, got " + std::to_string(start_time);
  }
  std::string e = First({trajectory.Validate(), kidnap ? kidnap->Validate() : "", sensor.Validate(),
                         gait.Validate(), odometry.Validate()});
  if (!e.empty()) return e;
  if (sensor.effects.ghosts.enabled && !scene.polished_floor)
    return "sensor.effects.ghosts: needs `scene.polished_floor: true` (no surface to mirror)";
  if (duration > 0.0) {  // (with duration 0 the route's end is known only once planned)
    std::ostringstream out;
    if (kidnap && kidnap->time >= duration) {
      out << "kidnap.time: must be before the end of the bag (duration " << duration << " s), got "
          << kidnap->time;
    }
    for (std::size_t i = 0; i < sensor.dropouts.size() && out.str().empty(); ++i) {
      if (sensor.dropouts[i].start >= duration) {
        out << "sensor.dropouts[" << i << "]: must start before the end of the bag (duration "
            << duration << " s), got " << sensor.dropouts[i].start;
      }
    }
    if (!out.str().empty()) return out.str();
  }
  for (std::size_t i = 0; i < scene.deviations.size(); ++i) {
    const DeviationConfig& d = scene.deviations[i];
    const std::string f = "scene.deviations[" + std::to_string(i) + "]";
    if (d.type == DeviationConfig::Type::kCloseDoorway) {
      if (d.doorway.name.empty() && d.doorway.id < 0)
        return f + ".doorway: missing (a doorway name or A-Graph doorway id)";
      e = Range(f + ".height", d.height, 0.0, 20.0, "m");
      if (!e.empty()) return e;
      continue;
    }
    if (d.type != DeviationConfig::Type::kAddWall && d.wall.name.empty() && d.wall.id < 0) {
      return f + ".wall: missing (a wall name or A-Graph wall id)";
    }
    if (d.type == DeviationConfig::Type::kAddWall) {
      if ((d.end - d.start).norm() < 0.05) return f + ".end: the wall is shorter than 5 cm";
      e = First({Positive(f + ".thickness", d.thickness, 2.0, "m"),
                 Range(f + ".height", d.height, 0.0, 20.0, "m")});
      if (!e.empty()) return e;
    }
    if (d.type == DeviationConfig::Type::kMoveWall) {
      e = Range(f + ".offset", d.offset, -5.0, 5.0, "m");
      if (!e.empty()) return e;
    }
    if (d.type == DeviationConfig::Type::kRotateWall) {
      e = Range(f + ".angle_deg", d.angle_deg, -45.0, 45.0, "deg");
      if (!e.empty()) return e;
    }
  }
  for (std::size_t i = 0; i < scene.clutter.size(); ++i) {
    const ClutterConfig& c = scene.clutter[i];
    const std::string f = "scene.clutter[" + std::to_string(i) + "]";
    if (!c.position && c.room.empty()) return f + ": needs `position` or `room`";
    if (c.size.minCoeff() < 0.0) return f + ".size: must not be negative";
    e = First({Range(f + ".radius", c.radius, 0.0, 10.0, "m"),
               Range(f + ".height", c.height, 0.0, 20.0, "m"),
               Range(f + ".reflectivity", c.reflectivity, 0.0, 1.0)});
    if (!e.empty()) return e;
  }
  for (std::size_t i = 0; i < scene.outside.size(); ++i) {
    const OutsideObjectConfig& o = scene.outside[i];
    const std::string f = "scene.outside[" + std::to_string(i) + "]";
    if (o.size.minCoeff() < 0.0 || o.size.maxCoeff() > 500.0)
      return f + ".size: must be in [0, 500] m";
    e = First({Range(f + ".radius", o.radius, 0.0, 20.0, "m"),
               Range(f + ".height", o.height, 0.0, 100.0, "m"),
               Range(f + ".yaw_deg", o.yaw_deg, -360.0, 360.0, "deg"),
               Range(f + ".reflectivity", o.reflectivity, 0.0, 1.0)});
    if (!e.empty()) return e;
    if (!o.position.allFinite()) return f + ".position: must be finite";
  }
  for (std::size_t i = 0; i < scene.people.size(); ++i) {
    e = scene.people[i].Validate("scene.people[" + std::to_string(i) + "]");
    if (!e.empty()) return e;
  }
  for (std::size_t i = 0; i < scene.doors.size(); ++i) {
    e = scene.doors[i].Validate("scene.doors[" + std::to_string(i) + "]");
    if (!e.empty()) return e;
  }
  if (scene.random_clutter.count < 0 || scene.random_clutter.count > 10000) {
    return "scene.random_clutter.count: must be in [0, 10000]";
  }
  return First({Range("scene.wall_reflectivity", scene.wall_reflectivity, 0.0, 1.0),
                Range("scene.floor_reflectivity", scene.floor_reflectivity, 0.0, 1.0),
                scene.glass.Validate()});
}

}  // namespace sim
}  // namespace is_graphs
