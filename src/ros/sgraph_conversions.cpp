#include "sgraph_conversions.h"

#include <algorithm>
#include <cmath>

#include "id_conversions.h"
#include "point_conversions.h"
#include "pose_conversions.h"

namespace is_graphs {
namespace ros_conversions {
is_graphs::SGraph ToMsg(const sgraph::SGraph& graph) {
  is_graphs::SGraph msg;
  msg.revision = graph.revision;
  msg.odometry_scale = graph.odometry_scale;
  for (const auto& k : graph.keyframes) {
    is_graphs::Keyframe m;
    m.id = static_cast<uint32_t>(k.id);
    m.stamp = ros::Time(std::max(0.0, k.stamp));
    m.pose = ToPose(k.pose);
    m.odom_pose = ToPose(k.odom_pose);
    m.has_previous = k.previous >= 0;
    m.previous_id = static_cast<uint32_t>(std::max(k.previous, 0));
    m.relative_odom = ToPose(k.relative_odom);
    ToArray(k.odom_information, m.odom_information);
    m.level = k.level;
    m.slice.reserve(3 * k.slice.size());
    for (const Eigen::Vector3f& q : k.slice) m.slice.insert(m.slice.end(), {q.x(), q.y(), q.z()});
    msg.keyframes.push_back(m);
  }
  for (const auto& p : graph.planes) {
    is_graphs::SPlane m;
    m.id = static_cast<uint32_t>(p.id);
    m.normal = ToVector3(p.plane.normal);
    m.d = p.plane.d;
    m.orientation = static_cast<uint8_t>(p.orientation);
    ToArray(p.covariance, m.covariance);
    m.start = ToPoint(p.start, p.z_min);
    m.end = ToPoint(p.end, p.z_min);
    m.z_min = p.z_min;
    m.z_max = p.z_max;
    m.num_points = static_cast<uint32_t>(std::max(p.num_points, 0));
    msg.planes.push_back(m);
  }
  for (const auto& o : graph.observations) {
    is_graphs::PlaneObservation m;
    m.keyframe_id = static_cast<uint32_t>(o.keyframe);
    m.plane_id = static_cast<uint32_t>(o.plane);
    m.normal = ToVector3(o.local.normal);
    m.d = o.local.d;
    ToArray(o.information, m.information);
    msg.observations.push_back(m);
  }
  for (const auto& r : graph.rooms) {
    is_graphs::SRoom m;
    m.id = static_cast<uint32_t>(r.id);
    m.type = static_cast<uint8_t>(r.type);
    m.center = ToPoint(r.center);
    m.plane_ids = CastIds<uint32_t>(r.planes);
    m.keyframe_ids = CastIds<uint32_t>(r.keyframes);
    ToArray(r.information, m.information);
    msg.rooms.push_back(m);
  }
  for (const auto& f : graph.floors) {
    is_graphs::SFloor m;
    m.id = static_cast<uint32_t>(f.id);
    m.center = ToPoint(f.center);
    m.height = f.height;
    m.room_ids = CastIds<uint32_t>(f.rooms);
    msg.floors.push_back(m);
  }
  for (const auto& d : graph.doorways) {
    is_graphs::SDoorway m;
    m.id = static_cast<uint32_t>(d.id);
    m.position = ToPoint(d.position);
    m.width = d.width;
    m.room_ids = CastIds<uint32_t>(d.rooms);
    m.plane_ids = CastIds<uint32_t>(d.planes);
    m.keyframe_ids = CastIds<uint32_t>(d.keyframes);
    msg.doorways.push_back(m);
  }
  return msg;
}

sgraph::SGraph FromMsg(const is_graphs::SGraph& msg) {
  sgraph::SGraph graph;
  graph.revision = msg.revision;
  graph.stamp = msg.header.stamp.toSec();
  // 0 from a node older than the field: the odometry as it reads.
  const double scale = msg.odometry_scale;
  graph.odometry_scale = std::isfinite(scale) && scale > 0.5 && scale < 2.0 ? scale : 1.0;
  for (const auto& m : msg.keyframes) {
    sgraph::Keyframe k;
    k.id = static_cast<int>(m.id);
    k.stamp = m.stamp.toSec();
    k.pose = FromPose(m.pose);
    k.odom_pose = FromPose(m.odom_pose);
    k.previous = m.has_previous ? static_cast<int>(m.previous_id) : -1;
    k.relative_odom = FromPose(m.relative_odom);
    k.odom_information = FromArray<6, 6>(m.odom_information);
    k.level = m.level;
    // x y z triples; a trailing partial triple (a malformed message) is ignored.
    for (size_t i = 0; i + 2 < m.slice.size(); i += 3)
      if (std::isfinite(m.slice[i]) && std::isfinite(m.slice[i + 1]) &&
          std::isfinite(m.slice[i + 2]))
        k.slice.emplace_back(m.slice[i], m.slice[i + 1], m.slice[i + 2]);
    graph.keyframes.push_back(std::move(k));
  }
  for (const auto& m : msg.planes) {
    sgraph::Plane p;
    p.id = static_cast<int>(m.id);
    p.plane = geometry::Plane(FromVector3(m.normal), m.d);
    p.orientation = static_cast<geometry::Orientation>(m.orientation);
    p.covariance = FromArray<4, 4>(m.covariance);
    p.start = Eigen::Vector2d(m.start.x, m.start.y);
    p.end = Eigen::Vector2d(m.end.x, m.end.y);
    p.z_min = m.z_min;
    p.z_max = m.z_max;
    p.num_points = static_cast<int>(m.num_points);
    graph.planes.push_back(p);
  }
  for (const auto& m : msg.observations) {
    sgraph::PlaneObservation o;
    o.keyframe = static_cast<int>(m.keyframe_id);
    o.plane = static_cast<int>(m.plane_id);
    o.local = geometry::Plane(FromVector3(m.normal), m.d);
    o.information = FromArray<3, 3>(m.information);
    graph.observations.push_back(o);
  }
  for (const auto& m : msg.rooms) {
    sgraph::Room r;
    r.id = static_cast<int>(m.id);
    r.type = static_cast<sgraph::RoomType>(m.type);
    r.center = FromPoint(m.center);
    r.planes = CastIds<int>(m.plane_ids);
    r.keyframes = CastIds<int>(m.keyframe_ids);
    r.information = FromArray<3, 3>(m.information);
    graph.rooms.push_back(r);
  }
  for (const auto& m : msg.floors) {
    sgraph::Floor f;
    f.id = static_cast<int>(m.id);
    f.center = FromPoint(m.center);
    f.height = m.height;
    f.rooms = CastIds<int>(m.room_ids);
    graph.floors.push_back(f);
  }
  for (const auto& m : msg.doorways) {
    sgraph::Doorway d;
    d.id = static_cast<int>(m.id);
    d.position = FromPoint(m.position);
    d.width = m.width;
    d.rooms = CastIds<int>(m.room_ids);
    d.planes = CastIds<int>(m.plane_ids);
    d.keyframes = CastIds<int>(m.keyframe_ids);
    graph.doorways.push_back(d);
  }
  return graph;
}

}  // namespace ros_conversions
}  // namespace is_graphs
