#include "is_graphs/sim/simulation.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "is_graphs/agraph/agraph_queries.h"
#include "is_graphs/agraph/ifc_conversion.h"

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

}  // namespace

int Simulation::NumScans() const {
  return static_cast<int>(std::floor(duration * config.sensor.rotation_rate_hz + 1e-9));
}

std::string DefaultBimCacheDir(const std::string& base_dir) {
  const char* ros_home = std::getenv("ROS_HOME");
  if (ros_home && *ros_home) return std::string(ros_home) + "/is_graphs/bim_cache";
  return Resolve(base_dir.empty() ? "." : base_dir, ".ws/bim_cache");
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
  const Eigen::Vector2d d = b - a;
  const double length = d.norm();
  if (length < 1e-3) return "";
  const Eigen::Vector2d u = d / length;
  const Eigen::Vector2d side(-u.y(), u.x());
  for (double height : {0.35, 1.0}) {
    for (double lateral : {-0.2, 0.0, 0.2}) {
      const Eigen::Vector2d o = a + lateral * side;
      const Ray ray{Eigen::Vector3f(o.x(), o.y(), floor_z + height),
                    Eigen::Vector3f(u.x(), u.y(), 0.0f), static_cast<float>(length)};
      const RayHit hit = scene.Intersect(ray);
      if (hit.triangle >= 0) {
        return "blocked at " + Xy(o + hit.distance * u) + " (" + std::to_string(height) +
               " m above the floor)";
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
  sim->log.push_back("building " + sim->graph.building + ": " +
                     std::to_string(mesh.value().triangles.size()) + " triangles, storey " +
                     std::to_string(sim->storey) + " '" + sim->graph.storeys[sim->storey].name +
                     "'");

  // Route (on the planned A-Graph) and the floor under its start.
  const Result<Route> route = PlanRoute(sim->graph, sim->storey, config.trajectory);
  if (!route.ok()) return R::Error(route.error());
  sim->route = route.value();
  for (const std::string& line : sim->route.description) sim->log.push_back("route: " + line);
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

  // The route must be walkable in the scene as built (an added partition may close a door).
  Eigen::Vector2d from = sim->route.start.head<2>();
  for (std::size_t i = 0; i < sim->route.waypoints.size(); ++i) {
    const Eigen::Vector2d to = sim->route.waypoints[i].position;
    const std::string blocked = CheckWalkable(*sim->embree, from, to, sim->floor_z);
    if (!blocked.empty()) {
      return R::Error("trajectory: the walk from " + Xy(from) + " to " + Xy(to) + " is " + blocked +
                      " in the scene as built");
    }
    from = to;
  }

  // Motion: duration from the scenario (scaled), else the route's.
  const double wanted = config.duration * duration_scale;
  Result<Trajectory> trajectory =
      Trajectory::Build(sim->route.start, sim->route.waypoints, config.trajectory, wanted);
  if (!trajectory.ok()) return R::Error(trajectory.error());
  sim->duration = wanted > 0.0 ? wanted : trajectory.value().Duration();
  sim->log.push_back("trajectory: " + std::to_string(trajectory.value().PathLength()) + " m in " +
                     std::to_string(trajectory.value().Duration()) + " s; bag " +
                     std::to_string(sim->duration) + " s");
  sim->motion =
      std::make_unique<RobotMotion>(std::move(trajectory).value(), config.gait, sim->floor_z);

  sim->sensor = std::make_unique<Vlp16Model>(config.sensor);
  sim->base_T_velodyne.translation() = config.velodyne_offset;
  sim->scans = std::make_unique<ScanSimulator>(
      *sim->embree, sim->scene, *sim->sensor, *sim->motion, sim->base_T_velodyne,
      BodyBox{config.body_center, config.body_size}, config.seed);
  return R::Ok(std::move(sim));
}

}  // namespace sim
}  // namespace is_graphs
