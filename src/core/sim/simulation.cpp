#include "is_graphs/sim/simulation.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "is_graphs/agraph/agraph_queries.h"
#include "is_graphs/agraph/ifc_conversion.h"
#include "is_graphs/sim/stair_paths.h"

namespace is_graphs {
namespace sim {
namespace {

std::string Resolve(const std::string& base_dir, const std::string& path) {
  if (path.empty() || path[0] == '/' || base_dir.empty()) return path;
  return base_dir + "/" + path;
}

std::string Xy(const Eigen::Vector2d& p) {
  std::ostringstream out;
  out.precision(3);
  out << std::fixed << "(" << p.x() << ", " << p.y() << ")";
  return out.str();
}

// "" when every leg of `route` is walkable in the scene as built, else the error, naming
// `field` (an added partition may close a door).
std::string CheckRoute(const EmbreeScene& scene, const Route& route, double floor_z,
                       const std::string& field) {
  Eigen::Vector2d from = route.start.head<2>();
  for (const PlanarWaypoint& w : route.waypoints) {
    const std::string blocked = CheckWalkable(scene, from, w.position, floor_z);
    if (!blocked.empty()) {
      return field + ": the walk from " + Xy(from) + " to " + Xy(w.position) + " is " + blocked +
             " in the scene as built";
    }
    from = w.position;
  }
  return "";
}

// "" when every walk of the motion's first leg is walkable in the scene as built at the
// terrain's height (a stair flight's rays rise with it), else the error.
std::string CheckWalks(const EmbreeScene& scene, const RobotMotion& motion,
                       const TerrainProfile& terrain) {
  for (const Trajectory::Walk& w : motion.trajectory().Walks()) {
    const double length = (w.to - w.from).norm();
    const std::string blocked =
        CheckWalkable(scene, w.from, w.to, terrain.GroundAt(w.distance_begin),
                      terrain.GroundAt(w.distance_begin + length));
    if (!blocked.empty()) {
      return "trajectory: the walk from " + Xy(w.from) + " to " + Xy(w.to) + " is " + blocked +
             " in the scene as built";
    }
  }
  return "";
}

std::string Seconds(double s) {
  std::ostringstream out;
  out << s << " s";
  return out.str();
}

// The robot's motion over `wanted` s (0: until the route ends): the trajectory, and with a
// kidnap before the end, the carry to the second route. Sets sim->motion and sim->duration.
std::string BuildMotion(Simulation* sim, double wanted) {
  const ScenarioConfig& c = sim->config;
  const bool kidnapped = c.kidnap && (wanted <= 0.0 || c.kidnap->time < wanted);
  const double first_duration = kidnapped ? c.kidnap->time : wanted;
  Result<Trajectory> first =
      Trajectory::Build(sim->route.start, sim->route.waypoints, c.trajectory, first_duration);
  if (!first.ok()) return first.error();
  TerrainProfile terrain = TerrainProfile::Flat(sim->floor_z);
  if (c.trajectory.follow_terrain) {
    // The ground under the path, then the same path again with the stair flights walked slower
    // (its path is a prefix of the first: the ground is found again along it).
    const TerrainConfig tc;
    Result<TerrainProfile> ground =
        TerrainProfile::Build(*sim->embree, first.value(), sim->floor_z, tc);
    if (!ground.ok()) return "trajectory: " + ground.error();
    const LegSpeed slow = StairLegSpeed(first.value(), ground.value(), tc, c.trajectory.speed,
                                        c.trajectory.stairs_speed);
    first = Trajectory::Build(sim->route.start, sim->route.waypoints, c.trajectory, first_duration,
                              slow);
    if (!first.ok()) return first.error();
    ground = TerrainProfile::Build(*sim->embree, first.value(), sim->floor_z, tc);
    if (!ground.ok()) return "trajectory: " + ground.error();
    terrain = std::move(ground).value();
  }
  sim->log.push_back("trajectory: " + std::to_string(first.value().PathLength()) + " m in " +
                     std::to_string(first.value().Duration()) + " s");
  if (c.trajectory.follow_terrain) {
    double lo = sim->floor_z, hi = sim->floor_z;
    for (double s = 0.0; s <= first.value().PathLength(); s += 0.5) {
      lo = std::min(lo, terrain.GroundAt(s));
      hi = std::max(hi, terrain.GroundAt(s));
    }
    std::ostringstream out;
    out.precision(2);
    out << std::fixed << "terrain: the ground under the path from " << lo << " to " << hi << " m";
    sim->log.push_back(out.str());
  }
  sim->motion =
      std::make_unique<RobotMotion>(std::move(first).value(), c.gait, sim->floor_z, terrain);
  if (c.trajectory.follow_terrain) {
    if (const std::string e = CheckWalks(*sim->embree, *sim->motion, terrain); !e.empty()) return e;
  }
  if (c.kidnap && !kidnapped) {
    sim->log.push_back("kidnap: at " + Seconds(c.kidnap->time) + ", after the end of the bag (" +
                       Seconds(wanted) + "): not simulated");
  } else if (kidnapped) {
    const Route& r = *sim->kidnap_route;
    Result<Trajectory> second =
        Trajectory::Build(r.start, r.waypoints, c.kidnap->AsTrajectory(c.trajectory),
                          wanted > 0.0 ? wanted - c.kidnap->time : 0.0);
    if (!second.ok()) return "kidnap: " + second.error();
    const Eigen::Vector2d from = sim->motion->trajectory().StateAt(c.kidnap->time).pose.head<2>();
    sim->log.push_back("kidnap: at " + Seconds(c.kidnap->time) + " carried from " + Xy(from) +
                       " to " + Xy(r.start.head<2>()) + ", then " +
                       std::to_string(second.value().PathLength()) + " m in " +
                       std::to_string(second.value().Duration()) + " s");
    sim->motion->Carry(c.kidnap->time, std::move(second).value());
  }
  sim->duration = wanted > 0.0 ? wanted : sim->motion->Duration();
  sim->log.push_back("bag: " + Seconds(sim->duration));
  return "";
}

}  // namespace

int Simulation::NumScans() const {
  return static_cast<int>(std::floor(duration * config.sensor.rotation_rate_hz + 1e-9));
}

bool Simulation::ScanDropped(int k) const {
  // Overlap of [k, k + 1) periods with a window; 1 ns slack against k * period rounding.
  const double period = 1.0 / config.sensor.rotation_rate_hz;
  const double begin = k * period, end = (k + 1) * period;
  for (const TimeWindow& w : config.sensor.dropouts) {
    if (begin < w.end - 1e-9 && end > w.start + 1e-9) return true;
  }
  return false;
}

std::string DefaultBimCacheDir(const std::string& base_dir) {
  const char* ros_home = std::getenv("ROS_HOME");
  if (ros_home && *ros_home) return std::string(ros_home) + "/is_graphs/bim_cache";
  // The project's own workspace (.ws/, `make build`) keeps it; any other, like ROS, in ~/.ros.
  const std::string ws = Resolve(base_dir.empty() ? "." : base_dir, ".ws");
  if (std::filesystem::is_directory(ws)) return ws + "/bim_cache";
  const char* home = std::getenv("HOME");
  if (home && *home) return std::string(home) + "/.ros/is_graphs/bim_cache";
  return "/tmp/is_graphs/bim_cache";
}

std::optional<double> FloorHeightAt(const geometry::TriangleMesh& mesh, const Eigen::Vector2d& xy,
                                    double z_max) {
  std::optional<double> best;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    const Eigen::Vector3d& b = mesh.vertices[t[1]];
    const Eigen::Vector3d& c = mesh.vertices[t[2]];
    const Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.norm() < 1e-12 || n.z() / n.norm() < 0.9) continue;  // not an upward face
    // Barycentric test in xy.
    const double det = (b.y() - c.y()) * (a.x() - c.x()) + (c.x() - b.x()) * (a.y() - c.y());
    if (std::abs(det) < 1e-12) continue;
    const double l1 =
        ((b.y() - c.y()) * (xy.x() - c.x()) + (c.x() - b.x()) * (xy.y() - c.y())) / det;
    const double l2 =
        ((c.y() - a.y()) * (xy.x() - c.x()) + (a.x() - c.x()) * (xy.y() - c.y())) / det;
    const double l3 = 1.0 - l1 - l2;
    if (l1 < -1e-9 || l2 < -1e-9 || l3 < -1e-9) continue;
    const double z = l1 * a.z() + l2 * b.z() + l3 * c.z();
    if (z <= z_max && (!best || z > *best)) best = z;
  }
  return best;
}

std::string CheckWalkable(const EmbreeScene& scene, const Eigen::Vector2d& a,
                          const Eigen::Vector2d& b, double floor_z) {
  return CheckWalkable(scene, a, b, floor_z, floor_z);
}

std::string CheckWalkable(const EmbreeScene& scene, const Eigen::Vector2d& a,
                          const Eigen::Vector2d& b, double floor_a, double floor_b) {
  const Eigen::Vector2d d = b - a;
  const double length = d.norm();
  if (length < 1e-3) return "";
  const Eigen::Vector2d u = d / length;
  const Eigen::Vector2d side(-u.y(), u.x());
  // Along the incline from a's floor to b's (level when they are equal).
  const Eigen::Vector3d dir = Eigen::Vector3d(d.x(), d.y(), floor_b - floor_a).normalized();
  const double length3 = std::hypot(length, floor_b - floor_a);
  for (double height : {0.35, 1.0}) {
    for (double lateral : {-0.2, 0.0, 0.2}) {
      const Eigen::Vector2d o = a + lateral * side;
      const Ray ray{Eigen::Vector3f(o.x(), o.y(), floor_a + height), dir.cast<float>(),
                    static_cast<float>(length3)};
      const RayHit hit = scene.Intersect(ray);
      if (hit.triangle >= 0) {
        return "blocked at " + Xy(o + hit.distance * dir.head<2>()) + " (" +
               std::to_string(height) + " m above the floor)";
      }
    }
  }
  return "";
}

Result<std::unique_ptr<Simulation>> PrepareSimulation(const ScenarioConfig& config,
                                                      const std::string& cache_dir,
                                                      double duration_scale) {
  using R = Result<std::unique_ptr<Simulation>>;
  if (!(duration_scale > 0.0 && duration_scale <= 100.0)) {
    return R::Error("--duration-scale: must be in (0, 100], got " + std::to_string(duration_scale));
  }
  auto sim = std::make_unique<Simulation>();
  sim->config = config;

  // Planned BIM: A-Graph (+ mesh).
  agraph::IfcConversionConfig conversion;
  conversion.cache_dir = cache_dir;
  const std::string building = Resolve(config.base_dir, config.building);
  Result<agraph::AGraph> graph = agraph::LoadBim(building, conversion);
  if (!graph.ok()) return R::Error("building: " + graph.error());
  sim->graph = std::move(graph).value();
  if (sim->graph.mesh.empty()) return R::Error("building: " + building + " has no mesh");
  const Result<geometry::TriangleMesh> mesh = geometry::LoadObj(sim->graph.mesh);
  if (!mesh.ok()) return R::Error("building: " + mesh.error());
  const Result<int> storey = agraph::FindStorey(sim->graph, config.storey);
  if (!storey.ok()) return R::Error("storey: " + storey.error());
  sim->storey = storey.value();
  if (config.localizer_storey && !config.localizer_storey->empty()) {
    const Result<int> told = agraph::FindStorey(sim->graph, *config.localizer_storey);
    if (!told.ok()) return R::Error("localizer_storey: " + told.error());
  }
  sim->log.push_back("building " + sim->graph.building + ": " +
                     std::to_string(mesh.value().triangles.size()) + " triangles, storey " +
                     std::to_string(sim->storey) + " '" + sim->graph.storeys[sim->storey].name +
                     "'");

  // Route (on the planned A-Graph, its rooms on any storey: up and down the stairs the mesh
  // has) and the floor under its start.
  std::vector<StairPath> stairs;
  if (config.trajectory.waypoints.empty()) {
    std::vector<std::string> skipped;
    stairs = FindStairPaths(mesh.value(), sim->graph, StairPathConfig(), &skipped);
    for (const StairPath& st : stairs) {
      sim->log.push_back("stairs: " + st.name + " from '" + sim->graph.rooms[st.lower_room].name +
                         "' (" + sim->graph.storeys[st.lower_storey].name + ") up to '" +
                         sim->graph.rooms[st.upper_room].name + "' (" +
                         sim->graph.storeys[st.upper_storey].name + ")");
    }
    for (const std::string& line : skipped) sim->log.push_back("stairs: not walked: " + line);
  }
  const Result<Route> route =
      PlanRoute(sim->graph, sim->storey, config.trajectory, "trajectory", stairs);
  if (!route.ok()) return R::Error(route.error());
  sim->route = route.value();
  for (const std::string& line : sim->route.description) sim->log.push_back("route: " + line);
  if (sim->route.stairs_taken > 0 && !config.trajectory.follow_terrain) {
    sim->config.trajectory.follow_terrain = true;  // a route up or down stairs walks on them
    sim->log.push_back("route: takes " + std::to_string(sim->route.stairs_taken) +
                       " stair(s): trajectory.follow_terrain on");
  }
  if (config.kidnap) {  // the route after the carry
    const Result<Route> second = PlanRoute(
        sim->graph, sim->storey, config.kidnap->AsTrajectory(config.trajectory), "kidnap", stairs);
    if (!second.ok()) return R::Error(second.error());
    sim->kidnap_route = second.value();
    for (const std::string& line : second.value().description) {
      sim->log.push_back("kidnap route: " + line);
    }
  }
  const double elevation = sim->graph.storeys[sim->storey].elevation;
  sim->floor_z =
      FloorHeightAt(mesh.value(), sim->route.start.head<2>(), elevation + 1.0).value_or(elevation);

  // As-built scene.
  SceneReport report;
  Result<SceneMesh> scene = BuildScene(mesh.value(), sim->graph, sim->storey, sim->floor_z,
                                       config.scene, config.seed, &report);
  if (!scene.ok()) return R::Error(scene.error());
  sim->scene = std::move(scene).value();
  for (const std::string& line : report.lines) sim->log.push_back(line);
  Result<std::unique_ptr<EmbreeScene>> embree = EmbreeScene::Create(sim->scene);
  if (!embree.ok()) return R::Error(embree.error());
  sim->embree = std::move(embree).value();

  // The routes must be walkable in the scene as built (on stairs: checked on the terrain, below).
  std::string e = sim->config.trajectory.follow_terrain
                      ? ""
                      : CheckRoute(*sim->embree, sim->route, sim->floor_z, "trajectory");
  if (e.empty() && sim->kidnap_route) {
    e = CheckRoute(*sim->embree, *sim->kidnap_route, sim->floor_z, "kidnap");
  }
  if (!e.empty()) return R::Error(e);

  // Motion: duration from the scenario (scaled), else the route's.
  e = BuildMotion(sim.get(), config.duration * duration_scale);
  if (!e.empty()) return R::Error(e);

  sim->sensor = std::make_unique<LidarModel>(config.sensor);
  if (!config.sensor.dropouts.empty()) {
    int dropped = 0;
    for (int k = 0; k < sim->NumScans(); ++k) dropped += sim->ScanDropped(k) ? 1 : 0;
    sim->log.push_back("sensor.dropouts: " + std::to_string(dropped) + " of " +
                       std::to_string(sim->NumScans()) + " scans not published");
  }
  sim->base_T_mount.translation() = config.velodyne_offset;
  sim->base_T_sensor = sim->base_T_mount * sim->sensor->spec().mount_T_points;
  sim->scans = std::make_unique<ScanSimulator>(
      *sim->embree, sim->scene, *sim->sensor, *sim->motion, sim->base_T_sensor,
      BodyBox{config.body_center, config.body_size}, config.seed);
  sim->scans->SetGlass(config.scene.glass);
  if (!config.scene.people.empty() || !config.scene.doors.empty()) {
    const RobotMotion* motion = sim->motion.get();
    Result<Movers> movers =
        Movers::Create(config.scene.people, config.scene.doors, sim->graph, sim->storey,
                       sim->floor_z, *sim->embree, [motion](double t) {
                         return Eigen::Vector2d(motion->BasePose(t).translation().head<2>());
                       });
    if (!movers.ok()) return R::Error(movers.error());
    sim->movers = std::move(movers).value();
    for (const std::string& line : sim->movers.log()) sim->log.push_back(line);
    sim->scans->SetMovers(&sim->movers);
  }
  return R::Ok(std::move(sim));
}

}  // namespace sim
}  // namespace is_graphs
