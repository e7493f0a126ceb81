#pragma once

#include <ros/ros.h>

#include <stdexcept>
#include <string>

#include "is_graphs/common/odometry_guard.h"

namespace is_graphs {
namespace ros_params {

/// A parameter a user got wrong: the message names it. Nodes catch it in main, log it and exit.
class ParamError : public std::runtime_error {
 public:
  explicit ParamError(const std::string& what) : std::runtime_error(what) {}
};

/// Overwrites `value` (the config default) with the private parameter `name` when it is set;
/// a parameter of the wrong type is a ParamError, not a silent default.
template <typename T>
void Read(const ros::NodeHandle& nh, const std::string& name, T& value) {
  if (!nh.hasParam(name)) return;
  if (!nh.getParam(name, value)) {
    throw ParamError("parameter '" + nh.resolveName(name) + "' has the wrong type");
  }
}

void Read(const ros::NodeHandle& nh, const std::string& name, unsigned int& value);

/// The private parameter `name`, which must be set to a non-empty string.
std::string RequireString(const ros::NodeHandle& nh, const std::string& name);

/// The odometry guard's parameters (config/odometry_guard.yaml, loaded into every node that reads
/// odometry so that all agree): max_linear_speed, max_angular_speed, max_linear_acceleration,
/// max_angular_acceleration, odometry_linear_slack, odometry_angular_slack, step_confirm_time.
void ReadOdometryGuard(const ros::NodeHandle& nh, common::OdometryGuardConfig& config);

/// Throws ParamError naming the parameter when `error` (a config's Validate() result) is set.
void ThrowIfInvalid(const std::string& component, const std::string& error);

}  // namespace ros_params
}  // namespace is_graphs
