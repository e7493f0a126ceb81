#include "is_graphs/matching/synthetic_slice.h"

#include <cmath>
#include <limits>
#include <random>

namespace is_graphs {
namespace matching {

std::vector<Eigen::Vector2d> SimulatedSlice(const agraph::AGraph& g, int storey,
                                            const Pose2& robot_in_bim, const Pose2& bim_T_map,
                                            int rays, double max_range, double noise_sigma,
                                            std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  const Eigen::Vector2d o = robot_in_bim.t;
  const Eigen::Matrix2d map_R_bim = bim_T_map.R().transpose();
  std::vector<Eigen::Vector2d> points;
  for (int k = 0; k < rays; ++k) {
    const double angle = robot_in_bim.yaw + 2.0 * M_PI * k / rays;
    const Eigen::Vector2d dir(std::cos(angle), std::sin(angle));
    double nearest = std::numeric_limits<double>::infinity();
    for (const agraph::WallSurface& s : g.surfaces) {
      if (s.storey != storey) continue;
      // o + r dir = start + u (end - start), r > 0, u in [0, 1].
      const Eigen::Vector2d e = s.end - s.start, w = s.start - o;
      const double den = dir.x() * (-e.y()) - dir.y() * (-e.x());
      if (std::abs(den) < 1e-12) continue;  // parallel
      const double r = (w.x() * (-e.y()) - w.y() * (-e.x())) / den;
      const double u = (dir.x() * w.y() - dir.y() * w.x()) / den;
      if (r > 1e-9 && u >= 0.0 && u <= 1.0) nearest = std::min(nearest, r);
    }
    const double n = noise(rng);  // drawn for every ray: the noise of a ray is its seed's
    if (nearest > max_range) continue;
    const Eigen::Vector2d hit = o + (nearest + noise_sigma * n) * dir;
    points.push_back(map_R_bim * (hit - bim_T_map.t));
  }
  return points;
}

}  // namespace matching
}  // namespace is_graphs
