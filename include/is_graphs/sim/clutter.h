#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/common/result.h"
#include "is_graphs/sim/scenario_config.h"
#include "is_graphs/sim/scene.h"

namespace is_graphs {
namespace sim {

/// The geometry of one clutter object. Kinds and their defaults (a given size, radius, height
/// or reflectivity overrides them): box 0.6 x 0.4 x 0.5 m; pallet 1.2 x 0.8 x 0.15 m; column
/// 0.4 x 0.4 m floor to ceiling; scaffolding 2.5 x 0.8 x 2.0 m of poles, rails and a platform;
/// cylinder r 0.3 m, 1.0 m high; person a cylinder r 0.25 m, 1.75 m high.
struct ClutterShape {
  bool cylinder{false};
  bool scaffolding{false};
  Eigen::Vector3d size{Eigen::Vector3d::Zero()};  // box (x, y, z); cylinder (2r, 2r, h)
  float reflectivity{0.5f};
};

ClutterShape ClutterShapeOf(const ClutterConfig& config, double storey_height);

/// Adds the object standing on z = base_z at xy, turned by yaw.
void AddClutter(SceneMesh* mesh, const ClutterShape& shape, const Eigen::Vector2d& xy,
                double base_z, double yaw);

/// Places `config.count` random objects (seeded) in the given rooms (all rooms of the storey
/// when none), kept `wall_margin` off the walls and off the robot's paths from each room's
/// interior point to its doorways. Returns how many found a place.
Result<int> PlaceRandomClutter(SceneMesh* scene, const agraph::AGraph& graph, int storey,
                               double floor_z, double storey_height,
                               const RandomClutterConfig& config, std::uint64_t seed);

}  // namespace sim
}  // namespace is_graphs
