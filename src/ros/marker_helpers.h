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

/// One hue per layer, so that a person tells the layers apart at a glance (config/is_graphs.rviz,
/// docs/images/isgraph.png): the BIM's A-Graph blue, the robot's S-Graph orange, the matcher's
/// pairs green, the merged iS-Graph magenta; the robot itself is yellow (urdf/), its pose red.
/// Within a layer, shades and shapes tell the parts apart.
namespace palette {
inline std_msgs::ColorRGBA AGraph(float a = 1.0f) { return Rgba(0.25f, 0.5f, 1.0f, a); }
inline std_msgs::ColorRGBA AGraphLight(float a = 1.0f) { return Rgba(0.6f, 0.78f, 1.0f, a); }
inline std_msgs::ColorRGBA AGraphCyan(float a = 1.0f) { return Rgba(0.2f, 0.85f, 1.0f, a); }
inline std_msgs::ColorRGBA SGraph(float a = 1.0f) { return Rgba(1.0f, 0.45f, 0.05f, a); }
inline std_msgs::ColorRGBA SGraphDark(float a = 1.0f) { return Rgba(0.85f, 0.35f, 0.0f, a); }
inline std_msgs::ColorRGBA SGraphLight(float a = 1.0f) { return Rgba(1.0f, 0.7f, 0.4f, a); }
inline std_msgs::ColorRGBA Match(float a = 1.0f) { return Rgba(0.15f, 0.95f, 0.25f, a); }
inline std_msgs::ColorRGBA MatchOpen(float a = 1.0f) { return Rgba(0.8f, 0.8f, 0.8f, a); }
inline std_msgs::ColorRGBA Deviation(float a = 1.0f) { return Rgba(1.0f, 0.1f, 0.1f, a); }
inline std_msgs::ColorRGBA ISGraph(float a = 1.0f) { return Rgba(0.95f, 0.2f, 0.85f, a); }
inline std_msgs::ColorRGBA ISGraphLight(float a = 1.0f) { return Rgba(1.0f, 0.6f, 0.95f, a); }
}  // namespace palette

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
