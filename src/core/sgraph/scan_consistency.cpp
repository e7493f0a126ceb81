#include "is_graphs/sgraph/scan_consistency.h"

#include <algorithm>
#include <cmath>

#include "is_graphs/sgraph/plane_fit.h"

namespace is_graphs {
namespace sgraph {
namespace {

constexpr double kDeg = M_PI / 180.0;

/// One associated wall as the check sees it (plan view).
struct WallPair {
  int segment{0};
  double yaw{0.0};  // rad: rotation taking the observed normal onto the mapped one
  double tolerance{0.0};
};

/// Variance of a plane's heading (rotation of its normal about z), from its (n, d) covariance.
double YawVariance(const Eigen::Vector3d& n, const Eigen::Matrix4d& covariance) {
  const Eigen::Vector3d along = Eigen::Vector3d::UnitZ().cross(n);
  if (along.norm() < 1e-6) return 0.0;
  const Eigen::Vector2d b = TangentBasis(n).transpose() * along.normalized();
  return b.dot(TangentCovariance(n, covariance).topLeftCorner<2, 2>() * b);
}

bool PlanNormal(const Eigen::Vector3d& n, Eigen::Vector2d& out) {
  out = n.head<2>();
  if (out.norm() < 0.5) return false;  // not a wall
  out.normalize();
  return true;
}

double Wrap(double a) { return std::atan2(std::sin(a), std::cos(a)); }

std::vector<int> Agreeing(const std::vector<WallPair>& walls, double yaw) {
  std::vector<int> set;
  for (size_t i = 0; i < walls.size(); ++i)
    if (std::abs(Wrap(walls[i].yaw - yaw)) <= walls[i].tolerance)
      set.push_back(static_cast<int>(i));
  return set;
}

}  // namespace

ScanConsistency ContradictedWalls(const std::vector<PlaneSegment>& observed_in_map,
                                  const std::vector<MapPlaneView>& mapped,
                                  const std::vector<Association>& associations,
                                  const FrontendConfig& config) {
  ScanConsistency out;
  if (config.consistency_min_walls <= 0) return out;
  std::vector<WallPair> walls;
  for (size_t s = 0; s < observed_in_map.size(); ++s) {
    const PlaneSegment& o = observed_in_map[s];
    if (o.horizontal || associations[s].index < 0) continue;
    const MapPlaneView& m = mapped[associations[s].index];
    if (m.num_keyframes < config.consistency_min_keyframes) continue;
    Eigen::Vector2d on, mn;
    if (!PlanNormal(o.plane.normal, on) || !PlanNormal(m.plane.normal, mn)) continue;
    WallPair w;
    w.segment = static_cast<int>(s);
    w.yaw = std::atan2(on.x() * mn.y() - on.y() * mn.x(), on.dot(mn));
    const double sigma = std::sqrt(YawVariance(o.plane.normal, o.covariance) +
                                   YawVariance(m.plane.normal, m.covariance));
    w.tolerance = std::max(
        (config.consistency_angle_deg + config.consistency_angle_deg_per_m * m.walked_since) * kDeg,
        3.0 * sigma);
    walls.push_back(w);
  }
  const size_t n = walls.size();
  if (n < static_cast<size_t>(config.consistency_min_walls)) return out;

  // The rotation most walls agree with (each wall's own heading error tried in turn), refined
  // to their weighted mean.
  std::vector<int> best;
  for (const WallPair& candidate : walls) {
    std::vector<int> set = Agreeing(walls, candidate.yaw);
    if (set.size() > best.size()) best = std::move(set);
  }
  const double reference = walls[best.front()].yaw;
  double sum = 0.0, weight = 0.0;
  for (int i : best) {
    const double w = 1.0 / (walls[i].tolerance * walls[i].tolerance);
    sum += w * Wrap(walls[i].yaw - reference);
    weight += w;
  }
  out.yaw = Wrap(reference + sum / weight);
  const std::vector<int> agreeing = Agreeing(walls, out.yaw);
  out.support = static_cast<int>(agreeing.size());
  if (agreeing.size() < 2 || 2 * agreeing.size() <= n) return out;  // no clear majority
  for (size_t i = 0; i < n; ++i)
    if (!std::binary_search(agreeing.begin(), agreeing.end(), static_cast<int>(i)))
      out.contradicted.push_back(walls[i].segment);
  return out;
}

}  // namespace sgraph
}  // namespace is_graphs
