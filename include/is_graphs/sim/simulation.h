#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/common/result.h"
#include "is_graphs/geometry/triangle_mesh.h"
#include "is_graphs/sim/embree_scene.h"
#include "is_graphs/sim/gait.h"
#include "is_graphs/sim/lidar_model.h"
#include "is_graphs/sim/movers.h"
#include "is_graphs/sim/odometry_drift.h"
#include "is_graphs/sim/route_planner.h"
#include "is_graphs/sim/scan_simulator.h"
#include "is_graphs/sim/scenario_config.h"
#include "is_graphs/sim/scene.h"

namespace is_graphs {
namespace sim {

/// Everything one scenario needs, built once: the planned A-Graph and the as-built scene, the
/// route and the robot's motion, the sensor model and the scan simulator. Not copyable (the
/// simulator refers to its siblings).
struct Simulation {
  ScenarioConfig config;
  agraph::AGraph graph;  // planned (what the localizer gets)
  int storey{0};
  double floor_z{0.0};  // floor height under the start pose, bim
  SceneMesh scene;      // as built
  std::unique_ptr<EmbreeScene> embree;
  Route route;
  std::optional<Route> kidnap_route;  // the route after the carry (`kidnap`)
  std::unique_ptr<RobotMotion> motion;
  std::unique_ptr<LidarModel> sensor;
  // base_link <- the sensor's mount frame (tf_static) and <- the frame its points are in
  // (the same but for the Ouster: base_T_mount * spec().mount_T_points).
  Eigen::Isometry3d base_T_mount{Eigen::Isometry3d::Identity()};
  Eigen::Isometry3d base_T_sensor{Eigen::Isometry3d::Identity()};
  Movers movers;  // people, carts and doors that move (scene.people, scene.doors)
  std::unique_ptr<ScanSimulator> scans;
  double duration{0.0};          // of the bag, s
  std::vector<std::string> log;  // what was built, for the user

  /// Number of complete scans in the bag (published or dropped).
  int NumScans() const;
  /// True when scan k (sweeping [k, k + 1) scan periods) overlaps a `sensor.dropouts` window:
  /// it is not published.
  bool ScanDropped(int k) const;
  /// A fresh odometry model (the drift is a stateful walk over the 50 Hz samples).
  OdometryDrift MakeOdometry() const {
    return OdometryDrift(config.odometry, config.seed, floor_z);
  }
};

/// Where the converted IFC files are cached: $ROS_HOME/is_graphs/bim_cache when ROS_HOME is
/// set, else <base_dir>/.ws/bim_cache when <base_dir>/.ws is there (the project's own
/// workspace), else ~/.ros/is_graphs/bim_cache (ROS's default ROS_HOME).
std::string DefaultBimCacheDir(const std::string& base_dir);

/// Loads the building (converting an IFC through the cache), builds the scene with clutter and
/// deviations, plans the route and sets up the sensor. `duration_scale` multiplies the
/// scenario's duration (for quick runs). Errors name the YAML field where there is one.
Result<std::unique_ptr<Simulation>> PrepareSimulation(const ScenarioConfig& config,
                                                      const std::string& cache_dir,
                                                      double duration_scale = 1.0);

/// The height of the highest upward-facing surface of `mesh` below z_max at (x, y); nullopt
/// when there is none.
std::optional<double> FloorHeightAt(const geometry::TriangleMesh& mesh, const Eigen::Vector2d& xy,
                                    double z_max);

/// "" when the straight walk from a to b at floor_z is free of scene obstacles (rays at two
/// heights along the body's centre line and sides), else a description of the blocking point.
std::string CheckWalkable(const EmbreeScene& scene, const Eigen::Vector2d& a,
                          const Eigen::Vector2d& b, double floor_z);
/// The same on an incline: from `a` at floor height `floor_a` to `b` at `floor_b` (stairs).
std::string CheckWalkable(const EmbreeScene& scene, const Eigen::Vector2d& a,
                          const Eigen::Vector2d& b, double floor_a, double floor_b);

}  // namespace sim
}  // namespace is_graphs
