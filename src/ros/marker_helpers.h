#pragma once

#include <std_msgs/ColorRGBA.h>
#include <visualization_msgs/Marker.h>

#include <string>

namespace is_graphs {
namespace ros_markers {

inline std_msgs::ColorRGBA Rgba(float r, float g, float b, float a = 1.0f) {
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

/// A marker to fill: frame, namespace, type, uniform scale and colour set, id 0, ADD, identity.
inline visualization_msgs::Marker MakeMarker(const std::string& frame_id, const std::string& ns,
                                             int type, double scale,
                                             const std_msgs::ColorRGBA& color) {
  visualization_msgs::Marker m;
  m.header.frame_id = frame_id;
  m.ns = ns;
  m.id = 0;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.scale.x = m.scale.y = m.scale.z = scale;
  m.color = color;
  return m;
}

}  // namespace ros_markers
}  // namespace is_graphs
