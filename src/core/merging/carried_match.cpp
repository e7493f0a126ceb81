#include "is_graphs/merging/carried_match.h"

#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/surface_evidence.h"
#include "is_graphs/sim/room_geometry.h"

namespace is_graphs {
namespace merging {

Eigen::Isometry3d CarriedTransform(const Eigen::Isometry3d& bim_T_odom,
                                   const sgraph::SGraph& graph) {
  if (graph.keyframes.empty()) return bim_T_odom;
  const sgraph::Keyframe& k = graph.keyframes.back();
  const Eigen::Isometry3d map_T_odom = k.pose * k.odom_pose.inverse();
  // Gravity-aligned as B_x_M is: x, y, yaw and z.
  const Eigen::Isometry3d full = bim_T_odom * map_T_odom.inverse();
  const Eigen::Vector3d xi = geometry::ToXYYaw(full);
  return geometry::IsometryFromXYYaw(xi.x(), xi.y(), xi.z(), full.translation().z());
}

matching::GraphMatch CarriedMatch(const agraph::AGraph& building, const sgraph::SGraph& graph,
                                  const Eigen::Isometry3d& bim_T_map, int storey, int min_planes,
                                  const matching::MatcherConfig& config) {
  matching::GraphMatch match;
  match.a_graph_sha256 = building.source.sha256;
  match.s_graph_revision = graph.revision;
  match.bim_T_map = bim_T_map;
  match.storey = storey;
  match.hypotheses = 1;
  const matching::SurfaceEvidence evidence(building, config);
  matching::Pose2 pose;
  pose.yaw = geometry::Yaw(bim_T_map);
  pose.t = bim_T_map.translation().head<2>();
  int paired = 0;
  for (const matching::WallSegment& plane : matching::WallSegments(graph, config)) {
    const auto along = evidence.AlongSurfaces(plane, pose, storey);
    if (along.empty()) continue;
    ++paired;
    const double share = evidence.Share(plane, pose, storey);
    for (const auto& a : along) match.surface_pairs.push_back({a.id, plane.id, share});
    match.score += share;
  }
  // An S-room (not a corridor: its centre is vague along it) whose centre lands inside an
  // A-room of the storey, within centre_tolerance of that room's centre: the same room.
  for (const sgraph::Room& room : graph.rooms) {
    if (room.type != sgraph::RoomType::kRoom || !room.center.allFinite()) continue;
    const Eigen::Vector2d c = (bim_T_map * room.center).head<2>();
    for (const agraph::Room& a : building.rooms) {
      if (a.storey != storey || a.polygon.size() < 3 || !sim::PointInPolygon(a.polygon, c))
        continue;
      if ((a.center.head<2>() - c).norm() <= config.centre_tolerance)
        match.room_pairs.push_back({a.id, room.id, 1.0});
      break;
    }
  }
  match.status =
      paired >= min_planes ? matching::MatchStatus::kUnique : matching::MatchStatus::kNone;
  return match;
}

}  // namespace merging
}  // namespace is_graphs
