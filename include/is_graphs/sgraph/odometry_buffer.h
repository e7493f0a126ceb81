#pragma once

#include <Eigen/Geometry>
#include <deque>
#include <optional>

namespace is_graphs {
namespace sgraph {

/// Recent odometry poses (odom <- base_link) by time, interpolated for deskewing and keyframes.
class OdometryBuffer {
 public:
  explicit OdometryBuffer(double horizon = 5.0) : horizon_(horizon) {}

  /// Appends a sample; older samples beyond the horizon are dropped. Samples must come in
  /// time order (the caller handles time going backwards).
  void Add(double stamp, const Eigen::Isometry3d& pose);
  void Clear() { samples_.clear(); }
  bool empty() const { return samples_.empty(); }
  double latest_stamp() const { return samples_.empty() ? 0.0 : samples_.back().stamp; }

  /// The pose at `stamp`: interpolated between the neighbouring samples (slerp) when they are
  /// at most `max_gap` apart, the last pose when `stamp` is at most `max_extrapolation` after
  /// it; nullopt otherwise.
  std::optional<Eigen::Isometry3d> At(double stamp, double max_gap, double max_extrapolation) const;

 private:
  struct Sample {
    double stamp;
    Eigen::Isometry3d pose;
  };
  double horizon_;
  std::deque<Sample> samples_;
};

/// Interpolates between two poses (slerp on rotation, linear on translation), s in [0, 1].
Eigen::Isometry3d Interpolate(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double s);

}  // namespace sgraph
}  // namespace is_graphs
