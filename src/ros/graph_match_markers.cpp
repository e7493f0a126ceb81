#include "graph_match_markers.h"

#include <map>

#include "marker_helpers.h"
#include "point_conversions.h"

namespace is_graphs {
namespace ros_markers {
namespace {

using ros_conversions::ToPoint;

visualization_msgs::Marker Make(const GraphMatchMarkerStyle& style, const std::string& ns, int type,
                                const std_msgs::ColorRGBA& colour, double scale) {
  return MakeMarker(style.frame_id, ns, type, scale, colour);
}

/// A line from A-surface `a_id`'s middle to the point of S-plane `s_id` (moved into B by
/// `bim_T_map`, then by `lift`) nearest it: extents may be split or merged differently, the
/// planes are what was matched. False (nothing added) for an unknown id or a non-finite point.
bool AddSurfaceLine(int a_id, int s_id, const agraph::AGraph& a_graph,
                    const std::map<int, const sgraph::Plane*>& s_planes,
                    const Eigen::Isometry3d& bim_T_map, const Eigen::Vector3d& lift,
                    visualization_msgs::Marker* marker) {
  const auto s = s_planes.find(s_id);
  if (a_id < 0 || a_id >= static_cast<int>(a_graph.surfaces.size()) || s == s_planes.end())
    return false;
  const auto& a = a_graph.surfaces[a_id];
  const Eigen::Vector2d mid = 0.5 * (a.start + a.end);
  const Eigen::Vector3d a_point(mid.x(), mid.y(), 0.5 * (a.z_min + a.z_max));
  const Eigen::Vector3d s_point = s->second->plane.Transformed(bim_T_map).Project(a_point) + lift;
  if (!s_point.allFinite() || !a_point.allFinite()) return false;
  marker->points.push_back(ToPoint(a_point));
  marker->points.push_back(ToPoint(s_point));
  return true;
}

}  // namespace

visualization_msgs::MarkerArray BuildGraphMatchMarkers(const matching::GraphMatch& match,
                                                       const agraph::AGraph& a_graph,
                                                       const sgraph::SGraph& s_graph,
                                                       const GraphMatchMarkerStyle& style) {
  visualization_msgs::MarkerArray array;
  visualization_msgs::Marker clear;
  clear.header.frame_id = style.frame_id;
  clear.action = visualization_msgs::Marker::DELETEALL;
  array.markers.push_back(clear);

  const bool unique = match.status == matching::MatchStatus::kUnique;
  const auto colour = unique ? palette::Match() : palette::MatchOpen();
  const Eigen::Isometry3d& t = match.bim_T_map;
  const Eigen::Vector3d lift(0.0, 0.0, style.s_graph_lift);
  std::map<int, const sgraph::Room*> s_rooms;
  for (const auto& r : s_graph.rooms) s_rooms.emplace(r.id, &r);
  std::map<int, const sgraph::Plane*> s_planes;
  for (const auto& p : s_graph.planes) s_planes.emplace(p.id, &p);

  auto rooms = Make(style, "room_pairs", visualization_msgs::Marker::LINE_LIST, colour,
                    3.0 * style.line_width);
  auto centres = Make(style, "s_rooms", visualization_msgs::Marker::SPHERE_LIST, colour, 0.45);
  for (const auto& p : match.room_pairs) {
    const auto s = s_rooms.find(p.s_id);
    if (p.a_id < 0 || p.a_id >= static_cast<int>(a_graph.rooms.size()) || s == s_rooms.end())
      continue;
    const Eigen::Vector3d s_point = t * s->second->center + lift;
    if (!s_point.allFinite()) continue;
    rooms.points.push_back(ToPoint(a_graph.rooms[p.a_id].center));
    rooms.points.push_back(ToPoint(s_point));
    centres.points.push_back(ToPoint(s_point));
  }

  auto surfaces = Make(style, "surface_pairs", visualization_msgs::Marker::LINE_LIST,
                       Rgba(colour.r, colour.g, colour.b, 0.6f), style.line_width);
  for (const auto& p : match.surface_pairs)
    AddSurfaceLine(p.a_id, p.s_id, a_graph, s_planes, t, lift, &surfaces);

  auto doorways = Make(style, "doorway_pairs", visualization_msgs::Marker::LINE_LIST, colour,
                       2.0 * style.line_width);
  std::map<int, const sgraph::Doorway*> s_doorways;
  for (const auto& d : s_graph.doorways) s_doorways.emplace(d.id, &d);
  for (const auto& p : match.doorway_pairs) {
    const auto s = s_doorways.find(p.s_id);
    if (p.a_id < 0 || p.a_id >= static_cast<int>(a_graph.doorways.size()) || s == s_doorways.end())
      continue;
    const Eigen::Vector3d a_point = a_graph.doorways[p.a_id].position;
    const Eigen::Vector3d s_point = t * s->second->position + lift;
    if (!s_point.allFinite() || !a_point.allFinite()) continue;
    doorways.points.push_back(ToPoint(a_point));
    doorways.points.push_back(ToPoint(s_point));
  }

  // Walls off the plan: from the A-surface's middle to the S-plane where it was built, in the
  // BIM frame itself (not lifted), red.
  auto deviations = Make(style, "deviations", visualization_msgs::Marker::LINE_LIST,
                         palette::Deviation(), 3.0 * style.line_width);
  for (const auto& d : match.deviations)
    AddSurfaceLine(d.a_id, d.s_id, a_graph, s_planes, t, Eigen::Vector3d::Zero(), &deviations);

  auto text = Make(style, "status", visualization_msgs::Marker::TEXT_VIEW_FACING, colour, 0.5);
  Eigen::Vector3d text_at = Eigen::Vector3d::Zero();
  for (const auto& r : a_graph.rooms)
    text_at += r.center / std::max<size_t>(1, a_graph.rooms.size());
  text.pose.position = ToPoint(text_at + lift + Eigen::Vector3d(0, 0, 8.0));  // over the layers
  text.text = std::string(matching::ToString(match.status)) + " (" +
              std::to_string(match.hypotheses) + " hypotheses, S-Graph rev " +
              std::to_string(match.s_graph_revision) + ")";
  for (auto* m : {&rooms, &centres, &surfaces, &doorways, &deviations})
    if (!m->points.empty()) array.markers.push_back(*m);
  array.markers.push_back(text);
  return array;
}

}  // namespace ros_markers
}  // namespace is_graphs
