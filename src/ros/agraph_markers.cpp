#include "agraph_markers.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "marker_helpers.h"
#include "point_conversions.h"

namespace is_graphs {
namespace ros_markers {
namespace {

using visualization_msgs::Marker;

using ros_conversions::ToPoint;

Marker NewMarker(const AGraphMarkerStyle& style, const std::string& ns, int type, double scale) {
  return MakeMarker(style.frame_id, ns, type, scale, Rgba(1.f, 1.f, 1.f));
}

Eigen::Vector3d SurfaceCorner(const agraph::WallSurface& s, bool end, bool top) {
  const Eigen::Vector2d& xy = end ? s.end : s.start;
  return {xy.x(), xy.y(), top ? s.z_max : s.z_min};
}

Eigen::Vector3d SurfaceMiddle(const agraph::WallSurface& s) {
  const Eigen::Vector2d xy = 0.5 * (s.start + s.end);
  return {xy.x(), xy.y(), 0.5 * (s.z_min + s.z_max)};
}

}  // namespace

visualization_msgs::MarkerArray BuildAGraphMarkers(const agraph::AGraph& graph,
                                                   const AGraphMarkerStyle& style) {
  double top = -std::numeric_limits<double>::infinity();
  for (const auto& s : graph.surfaces) top = std::max(top, s.z_max);
  for (const auto& r : graph.rooms) top = std::max(top, r.z_max);
  if (!std::isfinite(top)) top = 0.0;
  const double wall_z = top + style.layer_spacing;
  const double room_z = top + 2.0 * style.layer_spacing;
  auto lifted = [](const Eigen::Vector3d& p, double z) { return Eigen::Vector3d(p.x(), p.y(), z); };

  Marker surfaces = NewMarker(style, "wall_surfaces", Marker::TRIANGLE_LIST, 1.0);
  Marker outlines = NewMarker(style, "surface_outlines", Marker::LINE_LIST, style.line_width);
  for (const auto& s : graph.surfaces) {
    const Eigen::Vector3d a = SurfaceCorner(s, false, false), b = SurfaceCorner(s, true, false),
                          c = SurfaceCorner(s, true, true), d = SurfaceCorner(s, false, true);
    for (const Eigen::Vector3d& p : {a, b, c, a, c, d}) {
      surfaces.points.push_back(ToPoint(p));
    }
    for (const auto& [p, q] :
         {std::make_pair(a, b), std::make_pair(b, c), std::make_pair(c, d), std::make_pair(d, a)}) {
      outlines.points.push_back(ToPoint(p));
      outlines.points.push_back(ToPoint(q));
    }
  }
  surfaces.color = palette::AGraph(style.surface_alpha);
  outlines.color = palette::AGraphLight(0.8f);

  Marker walls = NewMarker(style, "walls", Marker::SPHERE_LIST, style.node_scale);
  walls.color = palette::AGraphLight();
  Marker wall_edges = NewMarker(style, "wall_edges", Marker::LINE_LIST, style.line_width);
  wall_edges.color = palette::AGraphLight(0.5f);
  for (const auto& w : graph.walls) {
    const Eigen::Vector3d c = lifted(w.center, wall_z);
    walls.points.push_back(ToPoint(c));
    for (int sid : {w.surface_a, w.surface_b}) {
      if (sid < 0 || sid >= static_cast<int>(graph.surfaces.size())) continue;
      wall_edges.points.push_back(ToPoint(c));
      wall_edges.points.push_back(ToPoint(SurfaceMiddle(graph.surfaces[sid])));
    }
  }

  Marker rooms = NewMarker(style, "rooms", Marker::SPHERE_LIST, 2.0 * style.node_scale);
  rooms.color = palette::AGraph();
  Marker room_outlines = NewMarker(style, "room_outlines", Marker::LINE_LIST, style.line_width);
  room_outlines.color = palette::AGraph(0.9f);
  Marker room_edges = NewMarker(style, "room_edges", Marker::LINE_LIST, 0.5 * style.line_width);
  room_edges.color = palette::AGraph(0.5f);
  visualization_msgs::MarkerArray out;
  for (const auto& r : graph.rooms) {
    const Eigen::Vector3d c = lifted(r.center, room_z);
    rooms.points.push_back(ToPoint(c));
    for (size_t i = 0; i < r.polygon.size(); ++i) {
      const auto& p = r.polygon[i];
      const auto& q = r.polygon[(i + 1) % r.polygon.size()];
      room_outlines.points.push_back(ToPoint({p.x(), p.y(), r.z_min + 0.02}));
      room_outlines.points.push_back(ToPoint({q.x(), q.y(), r.z_min + 0.02}));
    }
    for (int wid : r.walls) {
      if (wid < 0 || wid >= static_cast<int>(graph.walls.size())) continue;
      room_edges.points.push_back(ToPoint(c));
      room_edges.points.push_back(ToPoint(lifted(graph.walls[wid].center, wall_z)));
    }
    if (style.draw_names) {
      Marker name = NewMarker(style, "room_names", Marker::TEXT_VIEW_FACING, 0.4);
      name.id = r.id;
      name.pose.position = ToPoint(c + Eigen::Vector3d(0, 0, 0.5));
      name.text = r.long_name.empty() ? r.name : r.name + " " + r.long_name;
      out.markers.push_back(name);
    }
  }

  Marker doorways = NewMarker(style, "doorways", Marker::CUBE_LIST, style.node_scale);
  doorways.color = palette::AGraphCyan();
  Marker doorway_edges = NewMarker(style, "doorway_edges", Marker::LINE_LIST, style.line_width);
  doorway_edges.color = palette::AGraphCyan(0.6f);
  for (const auto& d : graph.doorways) {
    const Eigen::Vector3d p = lifted(d.position, room_z);
    doorways.points.push_back(ToPoint(p));
    for (int rid : d.rooms) {
      if (rid < 0 || rid >= static_cast<int>(graph.rooms.size())) continue;
      doorway_edges.points.push_back(ToPoint(p));
      doorway_edges.points.push_back(ToPoint(lifted(graph.rooms[rid].center, room_z)));
    }
  }

  for (Marker* m : {&surfaces, &outlines, &walls, &wall_edges, &rooms, &room_outlines, &room_edges,
                    &doorways, &doorway_edges}) {
    // rviz rejects list markers without points; an empty layer is simply not drawn.
    if (!m->points.empty()) out.markers.push_back(*m);
  }
  return out;
}

}  // namespace ros_markers
}  // namespace is_graphs
