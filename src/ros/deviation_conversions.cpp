#include "deviation_conversions.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "marker_helpers.h"

namespace is_graphs {
namespace ros_conversions {
namespace {

geometry_msgs::Point Point(const Eigen::Vector2d& p, double z) {
  geometry_msgs::Point q;
  q.x = p.x(), q.y = p.y(), q.z = z;
  return q;
}

std_msgs::ColorRGBA StatusColour(merging::WallStatus s) {
  using merging::WallStatus;
  switch (s) {
    case WallStatus::kAsPlanned:
      return ros_markers::Rgba(0.2f, 0.8f, 0.2f);
    case WallStatus::kMoved:
      return ros_markers::Rgba(1.0f, 0.6f, 0.0f);
    case WallStatus::kNotBuilt:
      return ros_markers::Rgba(0.9f, 0.1f, 0.9f);
    case WallStatus::kExtra:
      return ros_markers::Rgba(0.1f, 0.4f, 1.0f);
    case WallStatus::kNotSeen:
      return ros_markers::Rgba(0.6f, 0.6f, 0.6f, 0.6f);
  }
  return ros_markers::Rgba(1, 1, 1);
}

std_msgs::ColorRGBA DoorColour(merging::DoorwayStatus s) {
  switch (s) {
    case merging::DoorwayStatus::kPresent:
      return ros_markers::Rgba(0.2f, 0.8f, 0.2f);
    case merging::DoorwayStatus::kClosed:
      return ros_markers::Rgba(0.9f, 0.1f, 0.1f);
    case merging::DoorwayStatus::kNotSeen:
      return ros_markers::Rgba(0.6f, 0.6f, 0.6f, 0.6f);
  }
  return ros_markers::Rgba(1, 1, 1);
}

}  // namespace

is_graphs::DoorwayDeviation ToMsg(const merging::DoorwayDeviation& d) {
  is_graphs::DoorwayDeviation m;
  m.doorway_id = d.doorway_id;
  m.guid = d.guid;
  m.name = d.name;
  m.kind = static_cast<uint8_t>(d.kind);
  m.wall_id = d.wall_id;
  m.status = static_cast<uint8_t>(d.status);
  m.position = Point(d.position, 0.0);
  m.width = d.width;
  m.walked_through = d.walked_through;
  m.rays_through = d.rays_through;
  m.blocked_views = d.blocked_views;
  for (int id : d.s_doorways) m.s_doorways.push_back(static_cast<uint32_t>(id));
  for (int id : d.s_planes) m.s_planes.push_back(static_cast<uint32_t>(id));
  return m;
}

is_graphs::WallDeviation ToMsg(const merging::WallDeviation& d) {
  is_graphs::WallDeviation m;
  m.wall_id = d.wall_id;
  m.guid = d.guid;
  m.name = d.name;
  m.status = static_cast<uint8_t>(d.status);
  m.offset = d.offset;
  m.angle = d.angle;
  m.sigma = d.sigma;
  m.start = Point(d.start, 0.0);
  m.end = Point(d.end, 0.0);
  for (int id : d.s_planes) m.s_planes.push_back(static_cast<uint32_t>(id));
  m.rays_through = d.rays_through;
  m.height = d.height;
  return m;
}

visualization_msgs::MarkerArray DeviationMarkers(
    const std::vector<merging::WallDeviation>& walls,
    const std::vector<merging::DoorwayDeviation>& doors, const std::string& frame_id,
    double heat_max) {
  using merging::WallStatus;
  visualization_msgs::MarkerArray out;
  auto text =
      ros_markers::MakeMarker(frame_id, "labels", visualization_msgs::Marker::TEXT_VIEW_FACING,
                              0.35, ros_markers::Rgba(1, 1, 1));
  text.action = visualization_msgs::Marker::DELETEALL;  // walls change status: start afresh
  out.markers.push_back(text);
  text.action = visualization_msgs::Marker::ADD;
  for (int s = 0; s <= static_cast<int>(WallStatus::kNotSeen); ++s) {
    const auto status = static_cast<WallStatus>(s);
    auto m =
        ros_markers::MakeMarker(frame_id, merging::ToString(status),
                                visualization_msgs::Marker::LINE_LIST, 0.12, StatusColour(status));
    for (const auto& w : walls) {
      if (w.status != status) continue;
      for (double z : {0.05, 2.5}) {  // the wall's foot and top edge
        m.points.push_back(Point(w.start, z));
        m.points.push_back(Point(w.end, z));
        auto c = StatusColour(status);
        if (status == WallStatus::kMoved) {  // heat: yellow -> red with |offset|
          const double f = std::clamp(std::abs(w.offset) / heat_max, 0.0, 1.0);
          c = ros_markers::Rgba(1.0f, static_cast<float>(1.0 - f), 0.0f);
        }
        m.colors.push_back(c), m.colors.push_back(c);
      }
    }
    if (!m.points.empty()) out.markers.push_back(m);
  }
  for (const auto& w : walls) {
    if (w.status == WallStatus::kAsPlanned || w.status == WallStatus::kNotSeen) continue;
    char label[96];
    if (w.status == WallStatus::kMoved)
      std::snprintf(label, sizeof(label), "%s %+.0f cm %+.1f deg", w.name.c_str(), w.offset * 100,
                    w.angle * 180 / M_PI);
    else
      std::snprintf(label, sizeof(label), "%s %s", w.name.c_str(), merging::ToString(w.status));
    text.text = label;
    text.pose.position = Point(0.5 * (w.start + w.end), 3.0);
    ++text.id;
    out.markers.push_back(text);
  }
  auto spheres =
      ros_markers::MakeMarker(frame_id, "doorways", visualization_msgs::Marker::SPHERE_LIST, 0.4,
                              DoorColour(merging::DoorwayStatus::kNotSeen));
  for (const auto& d : doors) {
    spheres.points.push_back(Point(d.position, 1.0));
    spheres.colors.push_back(DoorColour(d.status));
    if (d.status != merging::DoorwayStatus::kClosed) continue;
    text.text = d.name + " CLOSED";
    text.pose.position = Point(d.position, 2.4);
    ++text.id;
    out.markers.push_back(text);
  }
  if (!spheres.points.empty()) out.markers.push_back(spheres);
  return out;
}

}  // namespace ros_conversions
}  // namespace is_graphs
