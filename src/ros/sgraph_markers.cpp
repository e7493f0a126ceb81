#include "sgraph_markers.h"

#include <map>

#include "marker_helpers.h"
#include "point_conversions.h"

namespace is_graphs {
namespace ros_markers {
namespace {

using visualization_msgs::Marker;

Marker MakeMarker(const SGraphMarkerStyle& style, const std::string& ns, int type, double scale,
                  const std_msgs::ColorRGBA& colour) {
  return ros_markers::MakeMarker(style.frame_id, ns, type, scale, colour);
}

}  // namespace

visualization_msgs::MarkerArray BuildSGraphMarkers(const sgraph::SGraph& graph,
                                                   const SGraphMarkerStyle& style) {
  using ros_conversions::ToPoint;
  const double top = [&] {
    double z = 0.0;
    for (const auto& k : graph.keyframes) z = std::max(z, k.pose.translation().z());
    for (const auto& p : graph.planes) z = std::max(z, p.z_max);
    return z;
  }();
  const double plane_layer = top + style.layer_spacing;
  const double room_layer = plane_layer + style.layer_spacing;
  const double floor_layer = room_layer + style.layer_spacing;

  Marker keyframes =
      MakeMarker(style, "keyframes", Marker::SPHERE_LIST, style.node_scale, palette::SGraphDark());
  Marker odom = MakeMarker(style, "odometry_edges", Marker::LINE_STRIP, style.line_width,
                           palette::SGraphDark());
  std::map<int, Eigen::Vector3d> keyframe_at;
  for (const auto& k : graph.keyframes) {
    keyframe_at[k.id] = k.pose.translation();
    keyframes.points.push_back(ToPoint(k.pose.translation()));
    odom.points.push_back(ToPoint(k.pose.translation()));
  }
  Marker planes = MakeMarker(style, "planes", Marker::TRIANGLE_LIST, 1.0, palette::SGraph(0.75f));
  Marker plane_nodes = MakeMarker(style, "plane_nodes", Marker::SPHERE_LIST, style.node_scale,
                                  palette::SGraphLight());
  std::map<int, Eigen::Vector3d> plane_node_at;
  for (const auto& p : graph.planes) {
    if (p.orientation == geometry::Orientation::kHorizontal) continue;
    const Eigen::Vector3d a(p.start.x(), p.start.y(), p.z_min), b(p.end.x(), p.end.y(), p.z_min);
    const Eigen::Vector3d up(0, 0, std::max(p.z_max - p.z_min, 0.05));
    // Both windings: rviz culls back faces, and a plane is seen from either side.
    const Eigen::Vector3d c = b + up, d = a + up;
    for (const Eigen::Vector3d& v : {a, b, c, a, c, d, a, c, b, a, d, c})
      planes.points.push_back(ToPoint(v));
    Eigen::Vector3d node = 0.5 * (a + b);
    node.z() = plane_layer;
    plane_node_at[p.id] = node;
    plane_nodes.points.push_back(ToPoint(node));
  }
  Marker observations = MakeMarker(style, "observation_edges", Marker::LINE_LIST,
                                   style.line_width * 0.5, palette::SGraphLight(0.25f));
  for (const auto& o : graph.observations) {
    auto k = keyframe_at.find(o.keyframe);
    auto p = plane_node_at.find(o.plane);
    if (k == keyframe_at.end() || p == plane_node_at.end()) continue;
    observations.points.push_back(ToPoint(k->second));
    observations.points.push_back(ToPoint(p->second));
  }
  Marker rooms =
      MakeMarker(style, "rooms", Marker::SPHERE_LIST, 2.0 * style.node_scale, palette::SGraph());
  Marker corridors = MakeMarker(style, "corridors", Marker::SPHERE_LIST, 2.0 * style.node_scale,
                                palette::SGraphLight());
  Marker room_edges =
      MakeMarker(style, "room_edges", Marker::LINE_LIST, style.line_width, palette::SGraph(0.7f));
  std::map<int, Eigen::Vector3d> room_at;
  for (const auto& r : graph.rooms) {
    const Eigen::Vector3d c(r.center.x(), r.center.y(), room_layer);
    room_at[r.id] = c;
    (r.type == sgraph::RoomType::kCorridor ? corridors : rooms).points.push_back(ToPoint(c));
    for (int pid : r.planes) {
      auto p = plane_node_at.find(pid);
      if (p == plane_node_at.end()) continue;
      room_edges.points.push_back(ToPoint(c));
      room_edges.points.push_back(ToPoint(p->second));
    }
  }
  Marker floor = MakeMarker(style, "floor", Marker::SPHERE_LIST, 3.0 * style.node_scale,
                            palette::SGraphLight());
  Marker floor_edges = MakeMarker(style, "floor_edges", Marker::LINE_LIST, style.line_width,
                                  palette::SGraphLight(0.7f));
  for (const auto& f : graph.floors) {
    const Eigen::Vector3d c(f.center.x(), f.center.y(), floor_layer);
    floor.points.push_back(ToPoint(c));
    for (int rid : f.rooms) {
      auto r = room_at.find(rid);
      if (r == room_at.end()) continue;
      floor_edges.points.push_back(ToPoint(c));
      floor_edges.points.push_back(ToPoint(r->second));
    }
  }
  // Doorways walked through: a bar across the gap at floor height (0.9 m when the width is not
  // known), and a line up to each room it joins.
  Marker doorways = MakeMarker(style, "doorways", Marker::LINE_LIST, 3.0 * style.line_width,
                               palette::SGraphLight());
  Marker doorway_edges = MakeMarker(style, "doorway_edges", Marker::LINE_LIST, style.line_width,
                                    palette::SGraphLight(0.7f));
  std::map<int, const sgraph::Plane*> plane_by_id;
  for (const auto& p : graph.planes) plane_by_id[p.id] = &p;
  for (const auto& d : graph.doorways) {
    if (!d.position.allFinite()) continue;
    Eigen::Vector2d along = Eigen::Vector2d::UnitX();
    const auto p = d.planes.empty() ? plane_by_id.end() : plane_by_id.find(d.planes.front());
    if (p != plane_by_id.end())
      along = Eigen::Vector2d(-p->second->plane.normal.y(), p->second->plane.normal.x());
    if (along.norm() > 1e-6) along.normalize();
    const double half = 0.5 * (d.width > 0.0 ? d.width : 0.9);
    const Eigen::Vector3d a = d.position + half * Eigen::Vector3d(along.x(), along.y(), 0.0);
    const Eigen::Vector3d b = d.position - half * Eigen::Vector3d(along.x(), along.y(), 0.0);
    doorways.points.push_back(ToPoint(a));
    doorways.points.push_back(ToPoint(b));
    for (int rid : d.rooms) {
      auto r = room_at.find(rid);
      if (r == room_at.end()) continue;
      doorway_edges.points.push_back(ToPoint(d.position));
      doorway_edges.points.push_back(ToPoint(r->second));
    }
  }
  visualization_msgs::MarkerArray out;
  for (Marker* m : {&keyframes, &odom, &planes, &plane_nodes, &observations, &rooms, &corridors,
                    &room_edges, &floor, &floor_edges, &doorways, &doorway_edges}) {
    // Empty lists are published as DELETE so stale markers disappear after a reset.
    if (m->points.empty() || (m->type == Marker::LINE_STRIP && m->points.size() < 2))
      m->action = Marker::DELETE;
    out.markers.push_back(*m);
  }
  return out;
}

}  // namespace ros_markers
}  // namespace is_graphs
