#pragma once

#include <Eigen/Geometry>
#include <string>

namespace is_graphs {
namespace common {

/// What a legged robot's odometry can do between two messages. Spot-like defaults, with margin:
/// Spot walks at up to 1.6 m/s and turns at up to ~1.5 rad/s.
struct OdometryGuardConfig {
  double max_linear_speed{3.0};           // m/s
  double max_angular_speed{3.0};          // rad/s
  double max_linear_acceleration{10.0};   // m/s²
  double max_angular_acceleration{20.0};  // rad/s²
  // Allowance on top of the kinematic bound for each step (stamping jitter, noise).
  double linear_slack{0.05};   // m
  double angular_slack{0.05};  // rad
  // Messages rejected as a glitch that then move plausibly among themselves for this long are
  // a lasting step of the odometry frame (a driver that reset, a re-anchored estimator): the
  // step is bridged (the motion goes on from the last accepted pose) instead of rejecting every
  // message after it. 0: never bridged.
  double step_confirm_time{0.5};  // s
  // Odometry this much older than the newest is time going back (a restarted bag): the guard
  // starts over and the message is passed on (its readers reset).
  double time_reset_threshold{1.0};  // s

  /// "" when valid, else "<field> must be ..." (the field first).
  std::string Validate() const;
};

/// Checks odometry (odom <- base_link by stamp) message by message: non-finite values, stamps
/// not after the last, and motion faster than the robot can move (a glitch: the message is not
/// used and the pose is not extrapolated through it). Every reader of the odometry stream runs
/// one, with the same configuration, so that all agree on which messages count and on the
/// bridge of a lasting step: `odom_T_base` of an accepted message is the reading corrected by
/// `correction()` (identity until a step was bridged), continuous across the step.
class OdometryGuard {
 public:
  enum class Verdict {
    kAccepted,    // use `odom_T_base`
    kTimeBack,    // time went back: the guard started over; use `odom_T_base` and reset
    kNonFinite,   // a NaN or infinite stamp, position or orientation: skipped
    kOutOfOrder,  // stamp not after the last accepted one: skipped
    kGlitch,      // moved faster than the robot can: skipped
    kBridged,     // a lasting step was confirmed and bridged: use `odom_T_base`
  };
  struct Result {
    Verdict verdict{Verdict::kAccepted};
    Eigen::Isometry3d odom_T_base{Eigen::Isometry3d::Identity()};  // corrected; when usable
    std::string message;  // why a message was skipped or what was bridged; "" when accepted
    bool usable() const {
      return verdict == Verdict::kAccepted || verdict == Verdict::kTimeBack ||
             verdict == Verdict::kBridged;
    }
  };

  explicit OdometryGuard(const OdometryGuardConfig& config = {}) : config_(config) {}

  Result Check(double stamp, const Eigen::Isometry3d& odom_T_base);
  void Reset();

  /// odom_corrected <- odom_reading: what the bridges of lasting steps added up to.
  const Eigen::Isometry3d& correction() const { return correction_; }
  int rejected() const { return rejected_; }  // messages skipped since the start
  int bridged() const { return bridged_; }    // lasting steps bridged since the start
  double last_stamp() const { return has_last_ ? last_stamp_ : -1.0; }

 private:
  // The step between two readings is within what the robot can do in dt, given the speeds
  // before it; "" if so, else why not.
  std::string Implausible(double dt, const Eigen::Isometry3d& from, const Eigen::Isometry3d& to,
                          double linear_speed, double angular_speed) const;

  OdometryGuardConfig config_;
  Eigen::Isometry3d correction_{Eigen::Isometry3d::Identity()};
  bool has_last_{false};
  double last_stamp_{0.0};
  Eigen::Isometry3d last_reading_{Eigen::Isometry3d::Identity()};  // raw, last accepted
  double linear_speed_{0.0}, angular_speed_{0.0};                  // of the last accepted step
  Eigen::Isometry3d last_step_{Eigen::Isometry3d::Identity()};     // that step (base frame)
  double last_dt_{0.0};                                            // its time; 0: none
  // Rejected as a glitch, in a run that moves plausibly among its messages: a step candidate.
  bool has_pending_{false};
  double pending_first_stamp_{0.0}, pending_last_stamp_{0.0};
  Eigen::Isometry3d pending_first_{Eigen::Isometry3d::Identity()};
  Eigen::Isometry3d pending_last_{Eigen::Isometry3d::Identity()};
  int rejected_{0};
  int bridged_{0};
};

const char* ToString(OdometryGuard::Verdict verdict);

}  // namespace common
}  // namespace is_graphs
