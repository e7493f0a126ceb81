#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "is_graphs/sim/movers_config.h"
#include "is_graphs/sim/sensor_effects_config.h"

// The configuration of one simulated scenario (a bags/*.yaml file): building, trajectory,
// sensor, gait, odometry drift, scene changes, seed. Plain structs with defaults; each has a
// Validate() returning "" when valid, else an error naming the offending field by its YAML path
// (e.g. "trajectory.speed: must be in (0, 2] m/s, got -0.5").

namespace is_graphs {
namespace sim {

/// A time interval [start, end) in s after the bag start.
struct TimeWindow {
  double start{0.0};
  double end{0.0};
};

/// The LiDAR models the simulator knows (`sensor.model`), each published as its ROS driver does.
enum class LidarModelKind {
  kVlp16,     // "vlp16": Velodyne VLP-16, velodyne_pointcloud (the default)
  kOs1_64,    // "os1_64": Ouster OS1-64, ouster-ros
  kHesaiXt32  // "hesai_xt32": Hesai PandarXT-32, Hesai ROS driver
};
const char* ToString(LidarModelKind model);
std::optional<LidarModelKind> ParseLidarModel(const std::string& name);

/// A spinning LiDAR (`sensor`). The member defaults are the VLP-16's; LidarConfig::For gives
/// each model's data-sheet defaults, which a scenario's keys then override.
struct LidarConfig {
  LidarModelKind model{LidarModelKind::kVlp16};
  double rotation_rate_hz{10.0};       // scans per second
  double azimuth_resolution_deg{0.2};  // firing sequences (columns) per scan = 360 / this
  double min_range{0.4};               // m; closer returns are dropped (as the driver does)
  double max_range{100.0};             // m
  double range_noise_stddev{0.015};    // m, Gaussian (±3 cm at 2σ, the data sheet's accuracy)
  double range_resolution{0.002};      // m, the packet's distance unit; 0 disables quantization
  double max_incidence_deg{85.0};      // no return beyond this angle from the surface normal
  double dropout_probability{0.0};     // random missing returns
  double intensity_noise_stddev{2.0};  // on the model's intensity scale (VLP-16: 0..100)
  double azimuth_offset_deg{0.0};      // azimuth (clockwise, from +x) of each scan's first firing
  // Sensor outages (increasing, disjoint): a scan whose sweep overlaps one is not published.
  std::vector<TimeWindow> dropouts;
  SensorEffectsConfig effects;  // `effects:` range noise, mixed pixels, dark surfaces, ghosts
  std::string Validate() const;
  /// The model's defaults: vlp16 as above; os1_64: 1024 columns, 0.5-120 m, σ 1 cm, 1 mm;
  /// hesai_xt32: 2000 columns (0.18°), 0.05-120 m, σ 1 cm, 4 mm.
  static LidarConfig For(LidarModelKind model);
};

/// Walking gait superposed on the planned planar motion. Amplitudes apply at full activity
/// (walking at `full_activity_speed` or turning), scaled linearly below it; zero at rest.
struct GaitConfig {
  double step_frequency_hz{2.0};  // vertical bob and pitch frequency; roll at half of it
  double bob_amplitude{0.015};    // m
  double roll_amplitude_deg{2.0};
  double pitch_amplitude_deg{1.5};
  double full_activity_speed{0.3};  // m/s
  double standing_height{0.525};    // base_link above the floor
  std::string Validate() const;
};

/// One waypoint in bim: position, and optionally the heading to turn to on arrival.
struct WaypointConfig {
  Eigen::Vector2d position{Eigen::Vector2d::Zero()};
  std::optional<double> yaw;
};

struct StartConfig {
  std::string room;                     // start at this room's centre, or
  std::optional<Eigen::Vector3d> pose;  // (x, y, yaw) in bim
};

struct TrajectoryConfig {
  std::vector<std::string> rooms;         // visit in order (A-Graph room `name` or `long_name`)
  std::vector<WaypointConfig> waypoints;  // or explicit waypoints (exactly one of the two)
  StartConfig start;                      // default: the first room / the first waypoint
  double speed{0.8};                      // m/s cruise
  double acceleration{0.5};               // m/s²
  double turn_rate_deg{45.0};             // deg/s, turning in place
  double turn_acceleration_deg{90.0};     // deg/s²
  double pause{1.0};                      // s standing still at the start and at each waypoint
  double doorway_clearance{0.8};          // m: the approach points are this far from the wall face
  bool loop{false};                       // repeat the route back and forth until `duration`
  // Stairs (issue 22): the body's height and pitch follow the ground under the path (stair
  // flights, landings, the next storey's floor; sim/terrain.h) instead of the start's floor,
  // and walks that climb or descend are walked at `stairs_speed`. Routes across storeys are
  // given as waypoints along the stair's walking line.
  bool follow_terrain{false};
  double stairs_speed{0.3};  // m/s
  std::string Validate() const;
};

struct OdometryConfig {
  double rate_hz{50.0};
  double scale_error{0.0};              // travelled distance × (1 + scale_error)
  double yaw_bias_per_m{0.0};           // rad per metre walked
  double yaw_bias_per_s{0.0};           // rad per second
  double translation_random_walk{0.0};  // m / √m walked (per axis)
  double yaw_random_walk{0.0};          // rad / √m walked
  double z_scale_error{0.0};            // height climbed × (1 + z_scale_error) (stairs)
  std::string Validate() const;
};

/// Kidnapped robot: at `time` the robot is carried (instantly) to the start of a second route
/// and walks it with the trajectory's speeds and pause. The ground truth jumps; the odometry
/// does not see the carry (it holds its pose across the jump, then integrates the new walk).
struct KidnapConfig {
  double time{0.0};                       // s after the start, > 0
  std::vector<std::string> rooms;         // the second route, as `trajectory.rooms`, or
  std::vector<WaypointConfig> waypoints;  // as `trajectory.waypoints` (exactly one of the two)
  StartConfig start;                      // default: the first room / the first waypoint
  bool loop{false};                       // walk it back and forth until `duration`
  std::string Validate() const;
  /// The trajectory of the second route: `base`'s speeds and pause with this route.
  TrajectoryConfig AsTrajectory(const TrajectoryConfig& base) const;
};

/// A reference to an A-Graph wall: by `name` (must be unique on the storey) or by A-Graph `id`.
struct WallRef {
  std::string name;
  int id{-1};
};

/// BIM deviation: the scene differs from the planned BIM (the A-Graph stays the planned one).
struct DeviationConfig {
  enum class Type { kMoveWall, kRemoveWall, kAddWall, kRotateWall, kCloseDoorway };
  Type type{Type::kMoveWall};
  WallRef wall;           // move_wall, remove_wall, rotate_wall
  WallRef doorway;        // close_doorway: a door / opening by name (unique on the storey) or id
  double offset{0.0};     // move_wall: m along the wall's first surface normal
  double angle_deg{0.0};  // rotate_wall: about the vertical through the wall's centre, CCW
  Eigen::Vector2d start{Eigen::Vector2d::Zero()}, end{Eigen::Vector2d::Zero()};  // add_wall
  double thickness{0.1};                                                         // add_wall
  double height{0.0};  // add_wall, close_doorway: 0 = the storey height (close_doorway: a fill)
};

/// A clutter object standing on the floor. Shapes: box, cylinder; the named kinds (pallet,
/// person, column, scaffolding) fill in default sizes.
struct ClutterConfig {
  std::string type{"box"};  // box | cylinder | pallet | person | column | scaffolding
  std::optional<Eigen::Vector2d> position;  // in bim, or
  std::string room;                         // relative to this room's centre by `offset`
  Eigen::Vector2d offset{Eigen::Vector2d::Zero()};
  Eigen::Vector3d size{
      Eigen::Vector3d::Zero()};  // box/scaffolding (x, y, z); 0 = the kind's default
  double radius{0.0};            // cylinder; 0 = default
  double height{0.0};            // cylinder; 0 = default
  double yaw_deg{0.0};
  double reflectivity{0.0};  // 0 = the kind's default
};

/// Random clutter: `count` objects of `types` in `rooms` (all rooms of the storey when empty).
struct RandomClutterConfig {
  int count{0};
  std::vector<std::string> types{"box", "pallet", "person"};
  std::vector<std::string> rooms;
  double wall_margin{0.5};  // m kept free along the room's walls
};

/// Glass (a scenario's `scene.glass`, docs/simulator.md; sim/glass.h casts the beams): the
/// triangles of the mesh objects of `classes` are panes. A beam that hits a pane within
/// `return_max_angle_deg` of its normal returns off the glass itself with `return_probability` (the
/// weak return a VLP-16 gets at near-normal incidence); every other beam passes through it (up to
/// `max_layers` glass faces: a pane has two, a window's body more; past them the beam returns off
/// the last) and goes on to what lies behind, or to nothing. Each glass face draws once. The IFC
/// exporters put a window's frame and its glazing in one body: the frame passes beams too. Off
/// unless `enabled`: then the scene and every scan are as without this struct.
struct GlassConfig {
  bool enabled{false};
  std::vector<std::string> classes{"IfcWindow", "IfcCurtainWall", "IfcPlate"};
  double return_probability{0.3};
  double return_max_angle_deg{15.0};
  int max_layers{8};

  /// "" when valid, else "scene.glass.<field>: ..." (the field first).
  std::string Validate() const;
  /// Whether an IFC class (IFC4's "...StandardCase" subtypes with their class) is glass.
  bool IsGlass(const std::string& ifc_class) const;
};

/// An object of the world outside the building (a scenario's `scene.outside`), seen through its
/// windows and open doors (sim/outside_world.h). Kinds and their defaults (a given size, radius,
/// height or reflectivity overrides them): building 20 x 10 x 9 m (a facing block); car
/// 4.5 x 1.8 x 1.5 m; tree, a trunk r 0.15 m, 2.5 m high, under a crown r `radius` (1.5 m),
/// `height` (3 m) high; wall 10 x 0.3 x 2 m (a fence, a boundary wall). Each stands on `base_z`
/// (default: the ground, the lowest storey with rooms).
struct OutsideObjectConfig {
  std::string type{"building"};                       // building | car | tree | wall
  Eigen::Vector2d position{Eigen::Vector2d::Zero()};  // in bim
  Eigen::Vector3d size{Eigen::Vector3d::Zero()};      // building, car, wall; 0 = default
  double radius{0.0};                                 // tree's crown; 0 = default
  double height{0.0};                                 // tree's crown; 0 = default
  double yaw_deg{0.0};
  double reflectivity{0.0};  // 0 = the kind's default
  std::optional<double> base_z;
};

struct SceneConfig {
  std::vector<std::string> drop_classes{"IfcDoor"};  // mesh objects left out (open doorways)
  std::vector<DeviationConfig> deviations;
  std::vector<ClutterConfig> clutter;
  RandomClutterConfig random_clutter;
  double wall_reflectivity{0.45};
  double floor_reflectivity{0.25};
  GlassConfig glass;           // `glass:` present: windows let beams through
  bool polished_floor{false};  // floors (slabs) mirror beams: SceneMesh::polished, ghosts
  std::vector<OutsideObjectConfig> outside;  // the world outside: none by default
  std::vector<MoverConfig> people;           // people and carts who walk: none by default
  std::vector<SwingingDoorConfig> doors;     // doors that swing: none by default
};

struct ScenarioConfig {
  std::string name;
  std::string building;     // IFC or .agraph.json, resolved against base_dir
  std::string base_dir;     // the repository root (relative `building` paths start here)
  std::string storey{"0"};  // storey name or index
  // What the localizer is told (evaluation, rostests, make demo/report): a storey name or index,
  // or "" for the whole building (the storey to be identified). Unset: `storey`.
  std::optional<std::string> localizer_storey;
  std::uint64_t seed{1};
  double duration{0.0};       // s; 0 = until the route ends (+ the final pause)
  double start_time{1000.0};  // s, ROS time of the first message
  TrajectoryConfig trajectory;
  std::optional<KidnapConfig> kidnap;
  LidarConfig sensor;
  GaitConfig gait;
  OdometryConfig odometry;
  SceneConfig scene;
  // Sensor mount (base_link -> the sensor's mount frame: velodyne, os_sensor, hesai_lidar), from
  // urdf/spot_like.urdf.
  Eigen::Vector3d velodyne_offset{0.1, 0.0, 0.1877};
  // Self-filter: the robot body box in base_link (centre, full size); returns inside are dropped.
  // Body 1.1 x 0.5 x 0.2 m plus the legs down to the floor, with 1-2 cm margin (more would hide
  // the lowest beams, which pass just over the body's sides).
  Eigen::Vector3d body_center{0.0, 0.0, -0.22};
  Eigen::Vector3d body_size{1.14, 0.54, 0.66};

  /// Validates all sections; the first error, naming the field.
  std::string Validate() const;
};

}  // namespace sim
}  // namespace is_graphs
