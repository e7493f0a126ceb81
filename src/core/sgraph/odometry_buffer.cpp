#include "is_graphs/sgraph/odometry_buffer.h"

#include <algorithm>

namespace is_graphs {
namespace sgraph {

Eigen::Isometry3d Interpolate(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double s) {
  const Eigen::Quaterniond qa(a.linear());
  const Eigen::Quaterniond qb(b.linear());
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = qa.slerp(s, qb).toRotationMatrix();
  out.translation() = (1.0 - s) * a.translation() + s * b.translation();
  return out;
}

void OdometryBuffer::Add(double stamp, const Eigen::Isometry3d& pose) {
  samples_.push_back({stamp, pose});
  while (samples_.size() > 2 && samples_.front().stamp < stamp - horizon_) samples_.pop_front();
}

std::optional<Eigen::Isometry3d> OdometryBuffer::At(double stamp, double max_gap,
                                                    double max_extrapolation) const {
  if (samples_.empty()) return std::nullopt;
  if (stamp >= samples_.back().stamp) {
    if (stamp - samples_.back().stamp <= max_extrapolation) return samples_.back().pose;
    return std::nullopt;
  }
  if (stamp < samples_.front().stamp) {
    if (samples_.front().stamp - stamp <= max_extrapolation) return samples_.front().pose;
    return std::nullopt;
  }
  auto it = std::lower_bound(samples_.begin(), samples_.end(), stamp,
                             [](const Sample& s, double t) { return s.stamp < t; });
  if (it == samples_.begin()) return it->pose;
  const Sample& hi = *it;
  const Sample& lo = *(it - 1);
  const double span = hi.stamp - lo.stamp;
  if (span > max_gap) return std::nullopt;
  if (span <= 0.0) return hi.pose;
  return Interpolate(lo.pose, hi.pose, (stamp - lo.stamp) / span);
}

}  // namespace sgraph
}  // namespace is_graphs
