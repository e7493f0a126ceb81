#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "is_graphs/sim/embree_scene.h"
#include "is_graphs/sim/gait.h"
#include "is_graphs/sim/scene.h"
#include "is_graphs/sim/vlp16_model.h"

namespace is_graphs {
namespace sim {

/// One return, laid out as the velodyne_pointcloud driver's XYZIRT point (in the velodyne frame
/// at the pulse's own time; `time` after the scan stamp).
struct LidarPoint {
  float x, y, z, intensity;
  std::uint16_t ring;
  float time;
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

/// Ray-casts VLP-16 scans against the scene from the moving robot: each firing sequence is
/// cast from the sensor pose at its own time (motion distortion as a real sensor has it).
/// Beams that would hit the robot's body are masked once (the body is rigid in the sensor
/// frame), which is the self-filter. Scan i draws its noise from its own seeded stream, so a
/// scan does not depend on the others.
class ScanSimulator {
 public:
  ScanSimulator(const EmbreeScene& scene, const SceneMesh& mesh, const Vlp16Model& model,
                const RobotMotion& motion, const Eigen::Isometry3d& base_T_velodyne,
                const BodyBox& body, std::uint64_t seed);

  /// The scan starting at `stamp` (s after the trajectory start); `index` selects the stream.
  LidarScan Simulate(std::uint64_t index, double stamp) const;
  /// Fraction of beams the body masks (for the log and tests).
  double MaskedFraction() const;

 private:
  const EmbreeScene& scene_;
  const SceneMesh& mesh_;
  const Vlp16Model& model_;
  const RobotMotion& motion_;
  Eigen::Isometry3d base_T_velodyne_;
  std::uint64_t seed_;
  std::vector<std::uint8_t> masked_;  // per (firing, laser)
};

/// True when the ray origin + s·dir, s in [0, max_s], enters the axis-aligned box.
bool RayHitsBox(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                const Eigen::Vector3d& box_min, const Eigen::Vector3d& box_max, double max_s);

}  // namespace sim
}  // namespace is_graphs
