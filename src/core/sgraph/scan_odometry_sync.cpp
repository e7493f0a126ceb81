#include "is_graphs/sgraph/scan_odometry_sync.h"

#include <cmath>
#include <utility>

namespace is_graphs {
namespace sgraph {

double LastFiring(const Scan& scan) {
  double last = 0.0;
  if (scan.has_time)
    for (const auto& p : scan.points)
      if (std::isfinite(p.time) && p.time > last) last = p.time;
  return scan.stamp + last;
}

void ScanOdometrySync::Push(Scan scan, const Eigen::Isometry3d& base_T_sensor, double now) {
  PendingScan p;
  p.scan = std::move(scan);
  p.base_T_sensor = base_T_sensor;
  p.last_firing = LastFiring(p.scan);  // not per odometry message: a cloud has ~30k points
  p.arrival = now;
  pending_.push_back(std::move(p));
}

std::vector<PendingScan> ScanOdometrySync::Release(double odom_stamp, double now) {
  // Point times are float: a sweep's end may round a few microseconds past the odometry
  // message stamped at it.
  constexpr double kStampTolerance = 1e-4;  // s
  std::vector<PendingScan> out;
  while (!pending_.empty()) {
    PendingScan& front = pending_.front();
    const bool covered = front.last_firing <= odom_stamp + kStampTolerance;
    const bool waited = now - front.arrival >= max_wait_;
    const bool full = pending_.size() > max_pending_;
    if (!covered && !waited && !full) break;
    front.waited_out = !covered;
    out.push_back(std::move(front));
    pending_.pop_front();
  }
  return out;
}

}  // namespace sgraph
}  // namespace is_graphs
