#pragma once

#include <Eigen/Core>
#include <string>

namespace is_graphs {
namespace merging {

/// As msg/LocalizationStatus.msg.
enum class LocalizationState { kNotLocalized = 0, kLocalized = 1, kLost = 2, kDegraded = 3 };

const char* ToString(LocalizationState state);

/// The localization's life: not localized until the first merge, localized since when and after
/// how many metres walked, lost when a merge is contradicted (matching again).
class MergeState {
 public:
  /// The robot's position (odom frame) at `stamp` [s]: accumulates the distance walked.
  void AddOdometry(double stamp, const Eigen::Vector3d& position);
  /// A merge holds from `stamp` on. The first one records time and distance to localize.
  void SetLocalized(double stamp, const std::string& message);
  /// A merge was dropped (contradicted, or its inputs stopped): no pose until the next one.
  void SetLost(const std::string& message);
  /// Localized, but an input is late (InputWatchdog): the pose still holds, less trusted.
  /// Only from LOCALIZED (or DEGRADED: the message changes); SetLocalized goes back.
  void SetDegraded(const std::string& message);
  /// Back to not localized (a new building, or the S-Graph restarted); distance from zero.
  void Reset(const std::string& message);

  LocalizationState state() const { return state_; }
  bool localized() const { return state_ == LocalizationState::kLocalized; }
  /// LOCALIZED or DEGRADED: a pose is published.
  bool has_pose() const {
    return state_ == LocalizationState::kLocalized || state_ == LocalizationState::kDegraded;
  }
  double localized_since() const { return localized_since_; }
  double seconds_to_localize() const { return seconds_to_localize_; }
  double distance_to_localize() const { return distance_to_localize_; }
  double distance_walked() const { return distance_; }
  double first_stamp() const { return first_stamp_; }
  const std::string& message() const { return message_; }

 private:
  LocalizationState state_{LocalizationState::kNotLocalized};
  bool ever_localized_{false};
  bool has_position_{false};
  Eigen::Vector3d last_position_{Eigen::Vector3d::Zero()};
  double first_stamp_{-1.0};
  double distance_{0.0};
  double localized_since_{0.0};
  double seconds_to_localize_{0.0};
  double distance_to_localize_{0.0};
  std::string message_{"waiting for a unique match"};
};

}  // namespace merging
}  // namespace is_graphs
