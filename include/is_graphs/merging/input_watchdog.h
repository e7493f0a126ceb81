#pragma once

#include <string>

namespace is_graphs {
namespace merging {

/// When the merger stops trusting its pose: the inputs it extrapolates from are late.
struct WatchdogConfig {
  // Odometry or tf map -> odom (the S-Graph's heartbeat, sent at its tf_rate) older than this
  // [s, the clock of the stamps: simulated time on a bag]: DEGRADED; older than lost_after: LOST.
  double degraded_after{0.7};
  double lost_after{10.0};
  // Walked this far [m] since the newest S-Graph revision (the S-Graph makes a keyframe every
  // keyframe_distance, 0.8 m): DEGRADED; lost_distance: LOST.
  double max_distance_without_sgraph{3.0};
  double lost_distance_without_sgraph{15.0};
  // While DEGRADED the pose's σ grows with the distance walked since the newest revision, as
  // the odometry's error does: σ_xy += degraded_sigma_per_m · d, σ_yaw += ... · d.
  double degraded_sigma_per_m{0.05};
  double degraded_yaw_sigma_deg_per_m{1.0};

  /// "" when valid, else "<field> must be ..." (the field first).
  std::string Validate() const;
};

/// Ages of the merger's inputs against a clock: odometry (its stamps), tf map -> odom (its
/// stamps) and the S-Graph (the distance walked since its newest revision). Plain data: the node
/// feeds it and asks Check on a timer and on each odometry message.
class InputWatchdog {
 public:
  enum class Health { kFresh = 0, kLate = 1, kStopped = 2 };
  struct Report {
    Health health{Health::kFresh};
    std::string message;                             // which input, how late; "" when fresh
    double odometry_age{0.0}, map_to_odom_age{0.0};  // s
    double distance_since_sgraph{0.0};               // m
  };

  explicit InputWatchdog(const WatchdogConfig& config = {}) : config_(config) {}

  /// Starts watching at `now` (every input counts as just seen): on localizing.
  void Arm(double now, double distance_walked);
  void OnOdometry(double stamp, double distance_walked);
  void OnMapToOdom(double stamp);
  void OnSGraph(double distance_walked);

  Report Check(double now) const;
  const WatchdogConfig& config() const { return config_; }

 private:
  WatchdogConfig config_;
  double odometry_stamp_{0.0};
  double map_to_odom_stamp_{0.0};
  double distance_{0.0};            // walked, at the newest odometry
  double distance_at_sgraph_{0.0};  // walked, when the newest S-Graph revision came
};

const char* ToString(InputWatchdog::Health health);

}  // namespace merging
}  // namespace is_graphs
