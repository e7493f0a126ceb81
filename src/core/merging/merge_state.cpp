#include "is_graphs/merging/merge_state.h"

namespace is_graphs {
namespace merging {

const char* ToString(LocalizationState state) {
  switch (state) {
    case LocalizationState::kNotLocalized:
      return "NOT_LOCALIZED";
    case LocalizationState::kLocalized:
      return "LOCALIZED";
    case LocalizationState::kLost:
      return "LOST";
    case LocalizationState::kDegraded:
      return "DEGRADED";
  }
  return "?";
}

void MergeState::AddOdometry(double stamp, const Eigen::Vector3d& position) {
  if (first_stamp_ < 0.0) first_stamp_ = stamp;
  if (has_position_) distance_ += (position - last_position_).head<2>().norm();
  last_position_ = position;
  has_position_ = true;
}

void MergeState::SetLocalized(double stamp, const std::string& message) {
  if (!has_pose()) localized_since_ = stamp;  // DEGRADED and back: localized all along
  if (!ever_localized_) {
    ever_localized_ = true;
    seconds_to_localize_ = first_stamp_ >= 0.0 ? stamp - first_stamp_ : 0.0;
    distance_to_localize_ = distance_;
  }
  state_ = LocalizationState::kLocalized;
  message_ = message;
}

void MergeState::SetDegraded(const std::string& message) {
  if (!has_pose()) return;
  state_ = LocalizationState::kDegraded;
  message_ = message;
}

void MergeState::SetLost(const std::string& message) {
  state_ = LocalizationState::kLost;
  message_ = message;
}

void MergeState::Reset(const std::string& message) {
  *this = MergeState();
  message_ = message;
}

}  // namespace merging
}  // namespace is_graphs
