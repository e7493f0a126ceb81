#include "is_graphs/sgraph/corridor_detection.h"

#include <algorithm>
#include <cmath>

namespace is_graphs {
namespace sgraph {

std::optional<RoomCandidate> DetectCorridor(const std::vector<Wall2D>& walls,
                                            const Eigen::Vector2d& position, const RayFan& fan,
                                            const FrontendConfig& config) {
  const int n = static_cast<int>(fan.hit.size());
  if (n == 0) return std::nullopt;
  const std::vector<int> count = CountHits(fan, walls.size());
  const double escape_cos = std::cos(35.0 * M_PI / 180.0);
  std::optional<RoomCandidate> best;
  double best_coverage = 0.0;
  for (size_t i = 0; i < walls.size(); ++i) {
    if (count[i] < n / 5) continue;
    for (size_t j = i + 1; j < walls.size(); ++j) {
      if (count[j] < n / 5) continue;
      const Wall2D& a = walls[i];
      const Wall2D& b = walls[j];
      if (a.normal.dot(b.normal) > -std::cos(0.1)) continue;  // not opposed parallel
      const double da = a.normal.dot(position) - a.d;
      const double db = b.normal.dot(position) - b.d;
      const double width = da + db;
      if (da <= 0.0 || db <= 0.0 || width < config.room_min_width ||
          width > config.corridor_max_width)
        continue;
      const Eigen::Vector2d axis(-a.normal.y(), a.normal.x());
      bool along = true;
      for (int k = 0; k < n && along; ++k) {
        const int h = fan.hit[k];
        if (h == static_cast<int>(i) || h == static_cast<int>(j)) continue;
        along = std::abs(axis.dot(fan.directions[k])) >= escape_cos;
      }
      if (!along) continue;
      const double coverage = count[i] + count[j];
      if (coverage <= best_coverage) continue;
      // Common extent of the two walls along the axis: the centre sits in its middle.
      const double a0 = axis.dot(a.start), a1 = axis.dot(a.end);
      const double b0 = axis.dot(b.start), b1 = axis.dot(b.end);
      const double lo = std::max(std::min(a0, a1), std::min(b0, b1));
      const double hi = std::min(std::max(a0, a1), std::max(b0, b1));
      const double s = lo < hi ? 0.5 * (lo + hi) : axis.dot(position);
      // On the mid-line: n_a·ρ − d_a = width / 2.
      const double offset = a.normal.dot(position) - a.d - 0.5 * width;
      RoomCandidate c;
      c.type = RoomType::kCorridor;
      c.axis = axis;
      c.center = position - offset * a.normal + (s - axis.dot(position)) * axis;
      c.walls = {a.id, b.id};
      c.distances = {a.normal.dot(c.center) - a.d, b.normal.dot(c.center) - b.d};
      best = c;
      best_coverage = coverage;
    }
  }
  return best;
}

}  // namespace sgraph
}  // namespace is_graphs
