#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "is_graphs/sim/embree_scene.h"
#include "is_graphs/sim/gait.h"
#include "is_graphs/sim/lidar_model.h"
#include "is_graphs/sim/movers.h"
#include "is_graphs/sim/scene.h"

namespace is_graphs {
namespace sim {

/// One return (XYZIRT as the velodyne_pointcloud driver's point, in the sensor's point frame at
/// the pulse's own time; `time` after the scan stamp), with the firing sequence (column) it
/// came from: the bag writer lays the drivers' organized clouds out by it.
struct LidarPoint {
  float x, y, z, intensity;
  std::uint16_t ring;
  float time;
  std::uint32_t column;
};

struct LidarScan {
  double stamp{0.0};               // scan start, s after the trajectory start
  std::vector<LidarPoint> points;  // in firing order
};

/// Box in base_link (the robot body with its legs): returns from inside are dropped.
struct BodyBox {
  Eigen::Vector3d center{Eigen::Vector3d::Zero()};
  Eigen::Vector3d size{Eigen::Vector3d::Zero()};
};

/// Ray-casts LiDAR scans against the scene from the moving robot: each firing sequence is
/// cast from the sensor pose at its own time (motion distortion as a real sensor has it).
/// Beams that would hit the robot's body are masked once (the body is rigid in the sensor
/// frame), which is the self-filter. Scan i draws its noise from its own seeded stream, so a
/// scan does not depend on the others.
class ScanSimulator {
 public:
  /// `base_T_sensor`: base_link <- the sensor's point frame.
  ScanSimulator(const EmbreeScene& scene, const SceneMesh& mesh, const LidarModel& model,
                const RobotMotion& motion, const Eigen::Isometry3d& base_T_sensor,
                const BodyBox& body, std::uint64_t seed);

  /// The scan starting at `stamp` (s after the trajectory start); `index` selects the stream.
  LidarScan Simulate(std::uint64_t index, double stamp) const;
  /// Fraction of beams the body masks (for the log and tests).
  double MaskedFraction() const;
  /// Beams pass the scene's panes (mesh.glass) as `glass` says; scan i draws from its own stream.
  void SetGlass(const GlassConfig& glass) { glass_ = glass; }
  /// People, carts and doors placed at each firing's time (nullptr or empty: none); not owned.
  void SetMovers(const Movers* movers) { movers_ = movers; }

 private:
  const EmbreeScene& scene_;
  const SceneMesh& mesh_;
  const LidarModel& model_;
  const RobotMotion& motion_;
  Eigen::Isometry3d base_T_sensor_;
  std::uint64_t seed_;
  GlassConfig glass_;  // disabled unless SetGlass
  const Movers* movers_{nullptr};
  std::vector<std::uint8_t> masked_;  // per (firing, laser)
};

/// True when the ray origin + s·dir, s in [0, max_s], enters the axis-aligned box.
bool RayHitsBox(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                const Eigen::Vector3d& box_min, const Eigen::Vector3d& box_max, double max_s);

}  // namespace sim
}  // namespace is_graphs
