#include "is_graphs/sgraph/evaluation.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>

#include "is_graphs/sgraph/odometry_buffer.h"

namespace is_graphs {
namespace sgraph {
namespace {

bool InsidePolygon(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p) {
  bool inside = false;
  for (size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

int RoomContaining(const agraph::AGraph& building, const Eigen::Vector2d& p) {
  for (size_t r = 0; r < building.rooms.size(); ++r)
    if (building.rooms[r].polygon.size() >= 3 && InsidePolygon(building.rooms[r].polygon, p))
      return static_cast<int>(r);
  return -1;
}

double Rmse(const std::vector<Eigen::Vector3d>& est, const std::vector<Eigen::Vector3d>& gt,
            const Eigen::Isometry3d& t) {
  double sum = 0.0;
  for (size_t i = 0; i < est.size(); ++i) sum += (t * est[i] - gt[i]).squaredNorm();
  return est.empty() ? 0.0 : std::sqrt(sum / est.size());
}

}  // namespace

std::optional<Eigen::Isometry3d> TruthAt(const std::vector<StampedPose>& truth, double stamp) {
  auto it = std::lower_bound(truth.begin(), truth.end(), stamp,
                             [](const StampedPose& s, double t) { return s.stamp < t; });
  if (it == truth.end() || it == truth.begin()) {
    if (it != truth.end() && std::abs(it->stamp - stamp) < 1e-6) return it->pose;
    return std::nullopt;
  }
  const StampedPose& hi = *it;
  const StampedPose& lo = *(it - 1);
  if (hi.stamp - lo.stamp > 0.2) return std::nullopt;
  return Interpolate(lo.pose, hi.pose, (stamp - lo.stamp) / std::max(hi.stamp - lo.stamp, 1e-9));
}

Eigen::Isometry3d AlignPositions(const std::vector<Eigen::Vector3d>& estimate,
                                 const std::vector<Eigen::Vector3d>& truth) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  if (estimate.size() < 3 || estimate.size() != truth.size()) {
    if (!estimate.empty() && estimate.size() == truth.size())
      t.translation() = truth[0] - estimate[0];
    return t;
  }
  Eigen::Matrix3Xd src(3, estimate.size()), dst(3, truth.size());
  for (size_t i = 0; i < estimate.size(); ++i) {
    src.col(i) = estimate[i];
    dst.col(i) = truth[i];
  }
  t.matrix() = Eigen::umeyama(src, dst, false);
  return t;
}

Eigen::Isometry3d AlignPositionsYaw(const std::vector<Eigen::Vector3d>& estimate,
                                    const std::vector<Eigen::Vector3d>& truth,
                                    const std::vector<double>& estimate_yaw,
                                    const std::vector<double>& truth_yaw) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  if (estimate.empty() || estimate.size() != truth.size()) return t;
  Eigen::Vector3d mean_e = Eigen::Vector3d::Zero(), mean_t = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < estimate.size(); ++i) mean_e += estimate[i], mean_t += truth[i];
  mean_e /= estimate.size();
  mean_t /= truth.size();
  // The yaw maximizing Σ (R e_i)·t_i over the horizontal parts of the centred points.
  double sin_sum = 0.0, cos_sum = 0.0;
  for (size_t i = 0; i < estimate.size(); ++i) {
    const Eigen::Vector2d e = (estimate[i] - mean_e).head<2>(), g = (truth[i] - mean_t).head<2>();
    cos_sum += e.dot(g);
    sin_sum += e.x() * g.y() - e.y() * g.x();
  }
  double spread = 0.0;
  for (const auto& e : estimate) spread = std::max(spread, (e - mean_e).head<2>().norm());
  double yaw = estimate.size() >= 2 ? std::atan2(sin_sum, cos_sum) : 0.0;
  if (spread < 0.5 && estimate_yaw.size() == estimate.size() &&
      truth_yaw.size() == estimate.size()) {
    // Too little walked to tell the yaw from the positions: the headings tell it.
    double s = 0.0, c = 0.0;
    for (size_t i = 0; i < estimate.size(); ++i) {
      s += std::sin(truth_yaw[i] - estimate_yaw[i]);
      c += std::cos(truth_yaw[i] - estimate_yaw[i]);
    }
    yaw = std::atan2(s, c);
  }
  t.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  t.translation() = mean_t - t.linear() * mean_e;
  return t;
}

TrajectoryError EvaluateTrajectory(const SGraph& graph, const std::vector<StampedPose>& truth) {
  TrajectoryError e;
  std::vector<Eigen::Vector3d> est, odom, gt;
  std::vector<double> est_yaw, odom_yaw, gt_yaw;
  auto yaw_of = [](const Eigen::Isometry3d& p) {
    return std::atan2(p.linear()(1, 0), p.linear()(0, 0));
  };
  for (const auto& k : graph.keyframes) {
    const auto t = TruthAt(truth, k.stamp);
    if (!t) continue;
    est.push_back(k.pose.translation());
    odom.push_back(k.odom_pose.translation());
    gt.push_back(t->translation());
    est_yaw.push_back(yaw_of(k.pose));
    odom_yaw.push_back(yaw_of(k.odom_pose));
    gt_yaw.push_back(yaw_of(*t));
  }
  e.keyframes = static_cast<int>(est.size());
  e.bim_T_map = AlignPositions(est, gt);
  e.sgraph_rmse = Rmse(est, gt, e.bim_T_map);
  e.odom_rmse = Rmse(odom, gt, AlignPositions(odom, gt));
  e.bim_T_map_gravity = AlignPositionsYaw(est, gt, est_yaw, gt_yaw);
  e.sgraph_rmse_gravity = Rmse(est, gt, e.bim_T_map_gravity);
  e.odom_rmse_gravity = Rmse(odom, gt, AlignPositionsYaw(odom, gt, odom_yaw, gt_yaw));
  return e;
}

std::vector<PlaneError> EvaluatePlanes(const SGraph& graph, const agraph::AGraph& building,
                                       const Eigen::Isometry3d& bim_T_map, int min_points) {
  std::vector<PlaneError> out;
  for (const auto& p : graph.planes) {
    if (p.orientation == geometry::Orientation::kHorizontal || p.num_points < min_points) continue;
    const geometry::Plane plane = p.plane.Transformed(bim_T_map);
    const double z = 0.5 * (p.z_min + p.z_max);
    const Eigen::Vector3d a = bim_T_map * Eigen::Vector3d(p.start.x(), p.start.y(), z);
    const Eigen::Vector3d b = bim_T_map * Eigen::Vector3d(p.end.x(), p.end.y(), z);
    PlaneError best;
    best.plane = p.id;
    best.distance = 1e9;
    for (const auto& s : building.surfaces) {
      const double cosine = plane.normal.dot(s.plane.normal);
      if (cosine < std::cos(10.0 * M_PI / 180.0)) continue;
      const double distance =
          std::max(std::abs(s.plane.SignedDistance(a)), std::abs(s.plane.SignedDistance(b)));
      if (distance > 0.3 || distance >= best.distance) continue;
      // The segment's middle must lie along the surface's extent (±0.5 m).
      const Eigen::Vector3d tangent = s.Tangent();
      const double m = tangent.dot(0.5 * (a + b));
      const double s0 = tangent.head<2>().dot(s.start), s1 = tangent.head<2>().dot(s.end);
      if (m < std::min(s0, s1) - 0.5 || m > std::max(s0, s1) + 0.5) continue;
      best.surface = s.id;
      best.distance = distance;
      best.angle_deg = std::acos(std::min(1.0, cosine)) * 180.0 / M_PI;
    }
    if (best.surface < 0) best.distance = 0.0;
    out.push_back(best);
  }
  return out;
}

RoomEvaluation EvaluateRooms(const SGraph& graph, const agraph::AGraph& building,
                             const std::vector<StampedPose>& truth,
                             const Eigen::Isometry3d& bim_T_map) {
  RoomEvaluation e;
  std::map<int, int> keyframes_in;  // A-Graph room -> keyframes inside it by ground truth
  for (const auto& k : graph.keyframes) {
    const auto t = TruthAt(truth, k.stamp);
    if (!t) continue;
    const int r = RoomContaining(building, t->translation().head<2>());
    if (r >= 0) ++keyframes_in[r];
  }
  std::map<int, bool> walked;
  for (const auto& [r, n] : keyframes_in)
    if (n >= 2) walked[r] = true;
  e.walked = static_cast<int>(walked.size());
  std::map<int, int> found;  // A-Graph room -> S-Graph rooms inside it
  for (const auto& room : graph.rooms) {
    ++e.detected;
    RoomVerdict v;
    v.room = room.id;
    v.center_bim = (bim_T_map * room.center).head<2>();
    const int at = RoomContaining(building, v.center_bim);
    v.a_room = at;
    if (at < 0 || !walked.count(at)) {
      ++e.false_rooms;
      v.kind = RoomVerdict::Kind::kOutside;
    } else if (found[at]++ > 0) {
      ++e.false_rooms;
      ++e.duplicates;
      v.kind = RoomVerdict::Kind::kDuplicate;
    }
    e.verdicts.push_back(v);
  }
  e.found = static_cast<int>(found.size());
  return e;
}

}  // namespace sgraph
}  // namespace is_graphs
