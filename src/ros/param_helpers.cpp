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

}  // namespace ros_params
}  // namespace is_graphs
