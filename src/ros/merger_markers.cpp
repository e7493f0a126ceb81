#include "merger_markers.h"

#include <map>

#include "marker_helpers.h"
#include "point_conversions.h"

namespace is_graphs {
namespace ros_markers {
namespace {

using ros_conversions::ToPoint;

visualization_msgs::Marker Make(const MergerMarkerStyle& style, const std::string& ns, int type,
                                double scale, const std_msgs::ColorRGBA& colour) {
  return MakeMarker(style.frame_id, ns, type, scale, colour);
}

Eigen::Vector3d Mid(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double z) {
  const Eigen::Vector2d m = 0.5 * (a + b);
  return {m.x(), m.y(), z};
}

}  // namespace

visualization_msgs::MarkerArray BuildMergerMarkers(const agraph::AGraph& a_graph,
                                                   const sgraph::SGraph& s_graph,
                                                   const merging::MatchPairs& pairs,
                                                   const Eigen::Isometry3d& bim_T_map,
                                                   const MergerMarkerStyle& style) {
  using visualization_msgs::Marker;
  const Eigen::Vector3d lift(0.0, 0.0, style.s_graph_lift);
  auto a_surfaces =
      Make(style, "a_graph/surfaces", Marker::LINE_LIST, 0.05, palette::AGraphLight(0.9f));
  std::map<int, Eigen::Vector3d> a_surface_mid;
  for (const auto& s : a_graph.surfaces) {
    a_surfaces.points.push_back(ToPoint(s.start, s.z_min));
    a_surfaces.points.push_back(ToPoint(s.end, s.z_min));
    a_surface_mid[s.id] = Mid(s.start, s.end, s.z_min);
  }
  auto a_rooms = Make(style, "a_graph/rooms", Marker::SPHERE_LIST, 0.3, palette::AGraph(0.9f));
  for (const auto& r : a_graph.rooms) a_rooms.points.push_back(ToPoint(r.center));

  auto s_planes = Make(style, "s_graph/planes", Marker::LINE_LIST, 0.08, palette::ISGraph());
  std::map<int, Eigen::Vector3d> s_plane_mid;
  for (const auto& p : s_graph.planes) {
    if (p.orientation == geometry::Orientation::kHorizontal) continue;
    const Eigen::Vector3d a = bim_T_map * Eigen::Vector3d(p.start.x(), p.start.y(), p.z_min) + lift;
    const Eigen::Vector3d b = bim_T_map * Eigen::Vector3d(p.end.x(), p.end.y(), p.z_min) + lift;
    s_planes.points.push_back(ToPoint(a));
    s_planes.points.push_back(ToPoint(b));
    s_plane_mid[p.id] = 0.5 * (a + b);
  }
  auto s_rooms = Make(style, "s_graph/rooms", Marker::SPHERE_LIST, 0.5, palette::ISGraph());
  std::map<int, Eigen::Vector3d> s_room_centre;
  for (const auto& r : s_graph.rooms) {
    s_room_centre[r.id] = bim_T_map * r.center + lift;
    s_rooms.points.push_back(ToPoint(s_room_centre[r.id]));
  }
  auto path =
      Make(style, "s_graph/keyframes", Marker::LINE_STRIP, 0.05, palette::ISGraphLight(0.9f));
  for (const auto& k : s_graph.keyframes)
    path.points.push_back(ToPoint(Eigen::Vector3d(bim_T_map * k.pose.translation() + lift)));

  auto edges = Make(style, "match", Marker::LINE_LIST, 0.03, palette::ISGraphLight(0.8f));
  for (const auto& [s_id, a_id] : pairs.rooms) {
    auto s = s_room_centre.find(s_id);
    if (s == s_room_centre.end() || a_id < 0 || a_id >= static_cast<int>(a_graph.rooms.size()))
      continue;
    edges.points.push_back(ToPoint(s->second));
    edges.points.push_back(ToPoint(a_graph.rooms[a_id].center));
  }
  for (const auto& [s_id, a_ids] : pairs.surfaces) {
    auto s = s_plane_mid.find(s_id);
    if (s == s_plane_mid.end()) continue;
    for (int a_id : a_ids) {
      auto a = a_surface_mid.find(a_id);
      if (a == a_surface_mid.end()) continue;
      edges.points.push_back(ToPoint(s->second));
      edges.points.push_back(ToPoint(a->second));
    }
  }
  visualization_msgs::MarkerArray out;
  for (auto* m : {&a_surfaces, &a_rooms, &s_planes, &s_rooms, &path, &edges})
    if (!m->points.empty()) out.markers.push_back(*m);
  return out;
}

}  // namespace ros_markers
}  // namespace is_graphs
