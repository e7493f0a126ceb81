#include "is_graphs/sim/lidar_specs.h"

#include <cmath>

namespace is_graphs {
namespace sim {

LidarSpec SpecFor(LidarModelKind model) {
  LidarSpec s;
  switch (model) {
    case LidarModelKind::kVlp16:
      // VLP-16 user manual, table 9-1 (laser id -> elevation) and 9.5 (firing timing).
      s.elevation_deg = {-15, 1, -13, 3, -11, 5, -9, 7, -7, 9, -5, 11, -3, 13, -1, 15};
      for (double e : s.elevation_deg) s.ring.push_back(static_cast<std::uint16_t>((e + 15) / 2));
      s.laser_interval = 2.304e-6;
      s.intensity_scale = 100.0;
      break;
    case LidarModelKind::kOs1_64:
      // OS1-64 (uniform beam spacing): 45 deg vertical field of view; ouster-ros puts the
      // highest beam in row 0. The columns fire all 64 beams at once.
      for (int i = 0; i < 64; ++i) {
        s.elevation_deg.push_back(22.5 - 45.0 * i / 63.0);
        s.ring.push_back(static_cast<std::uint16_t>(i));
      }
      s.laser_interval = 0.0;
      s.intensity_scale = 1000.0;  // signal photons; reflectivity is written apart (0..255)
      s.mount_T_points.linear() =
          Eigen::Matrix3d(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()));
      s.mount_T_points.translation() = Eigen::Vector3d(0.0, 0.0, 0.03618);
      break;
    case LidarModelKind::kHesaiXt32:
      // PandarXT-32 user manual: channels 1..32 at +15..-16 deg, 1 deg apart, fired in order
      // 1.512 us apart; the ROS driver's ring is the channel index from 0.
      for (int i = 0; i < 32; ++i) {
        s.elevation_deg.push_back(15.0 - i);
        s.ring.push_back(static_cast<std::uint16_t>(i));
      }
      s.laser_interval = 1.512e-6;
      s.intensity_scale = 255.0;
      break;
  }
  return s;
}

}  // namespace sim
}  // namespace is_graphs
