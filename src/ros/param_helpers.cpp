#include "param_helpers.h"

namespace is_graphs {
namespace ros_params {

void Read(const ros::NodeHandle& nh, const std::string& name, unsigned int& value) {
  int signed_value = static_cast<int>(value);
  Read(nh, name, signed_value);
  if (signed_value < 0) {
    throw ParamError("parameter '" + nh.resolveName(name) + "' must not be negative (got " +
                     std::to_string(signed_value) + ")");
  }
  value = static_cast<unsigned int>(signed_value);
}

std::string RequireString(const ros::NodeHandle& nh, const std::string& name) {
  std::string value;
  Read(nh, name, value);
  if (value.empty()) {
    throw ParamError("parameter '" + nh.resolveName(name) + "' is required and not set");
  }
  return value;
}

void ThrowIfInvalid(const std::string& component, const std::string& error) {
  if (!error.empty()) throw ParamError(component + ": " + error);
}

void ReadOdometryGuard(const ros::NodeHandle& nh, common::OdometryGuardConfig& config) {
  Read(nh, "max_linear_speed", config.max_linear_speed);
  Read(nh, "max_angular_speed", config.max_angular_speed);
  Read(nh, "max_linear_acceleration", config.max_linear_acceleration);
  Read(nh, "max_angular_acceleration", config.max_angular_acceleration);
  Read(nh, "odometry_linear_slack", config.linear_slack);
  Read(nh, "odometry_angular_slack", config.angular_slack);
  Read(nh, "step_confirm_time", config.step_confirm_time);
  std::string error = config.Validate();
  if (error.empty()) return;
  // The slacks carry an "odometry_" prefix as parameters.
  const std::string field = error.substr(0, error.find(' '));
  const std::string name = field.find("slack") != std::string::npos ? "odometry_" + field : field;
  throw ParamError("parameter '" + nh.resolveName(name) + "'" + error.substr(field.size()));
}

}  // namespace ros_params
}  // namespace is_graphs
