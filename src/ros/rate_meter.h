#pragma once
// Message rates for /diagnostics: counts per window of the node's clock (simulated time on a bag).
#include <ros/time.h>

#include <mutex>

namespace is_graphs {
namespace ros_diagnostics {

/// Counts events; Rate() is the mean rate since the previous call to Rate() (the diagnostic
/// period), so each /diagnostics message shows the rate over its own window. Thread-safe.
class RateMeter {
 public:
  void Tick() {
    std::lock_guard<std::mutex> lock(mutex_);
    ++count_;
    ++total_;
  }
  /// Events per second since the last call, 0 on the first call or a clock that stood still.
  double Rate(const ros::Time& now) {
    std::lock_guard<std::mutex> lock(mutex_);
    const double dt = window_start_.isZero() ? 0.0 : (now - window_start_).toSec();
    const double rate = dt > 0.0 ? count_ / dt : 0.0;
    window_start_ = now;
    count_ = 0;
    return rate;
  }
  long total() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return total_;
  }

 private:
  mutable std::mutex mutex_;
  ros::Time window_start_;
  long count_{0};
  long total_{0};
};

}  // namespace ros_diagnostics
}  // namespace is_graphs
