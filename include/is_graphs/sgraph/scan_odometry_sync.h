#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <deque>
#include <vector>

#include "is_graphs/sgraph/point_types.h"

namespace is_graphs {
namespace sgraph {

/// The time of a scan's last firing: its stamp plus the largest finite per-point time (the
/// stamp itself for a scan without per-point time).
double LastFiring(const Scan& scan);

/// A cloud held until odometry covers it.
struct PendingScan {
  Scan scan;
  Eigen::Isometry3d base_T_sensor{Eigen::Isometry3d::Identity()};
  double last_firing{0.0};  // LastFiring(scan), once
  double arrival{0.0};      // when it arrived, on the caller's monotonic clock [s]
  bool waited_out{false};   // released because odometry did not come within max_wait
};

/// Holds each cloud until odometry reaches its last firing, so that deskewing interpolates the
/// sweep instead of holding the last odometry pose over its end. On a live robot or a bag played
/// on a loaded machine a cloud can arrive before the odometry messages of its own sweep (two
/// topics, two connections): deskewed without them, a scan taken while turning at 40 deg/s has
/// its walls rotated by up to 3 deg (D5 at 2x with both cores busy: a keyframe 1.4 deg off in yaw).
/// A cloud waits at most `max_wait` seconds of the caller's clock and never behind a cloud still
/// waiting: order is kept. max_wait 0 releases every cloud at once.
class ScanOdometrySync {
 public:
  explicit ScanOdometrySync(double max_wait, std::size_t max_pending = 32)
      : max_wait_(max_wait), max_pending_(max_pending) {}

  void Push(Scan scan, const Eigen::Isometry3d& base_T_sensor, double now);
  /// The clouds ready now, oldest first (removed from the queue): covered by odometry up to
  /// `odom_stamp`, or waited max_wait, or pushed out by a full queue.
  std::vector<PendingScan> Release(double odom_stamp, double now);
  /// Drops every held cloud (the odometry restarted: they belong to the old run).
  void Clear() { pending_.clear(); }
  std::size_t size() const { return pending_.size(); }

 private:
  double max_wait_;
  std::size_t max_pending_;
  std::deque<PendingScan> pending_;
};

}  // namespace sgraph
}  // namespace is_graphs
