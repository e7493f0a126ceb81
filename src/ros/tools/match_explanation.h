// replay_pipeline --explain: how the S-Graph's rooms relate to the BIM's under the true motion
// (from the bag's ground truth): for each S-room, the A-room it lies in, how its planes fit that
// room, and the matcher's local candidates. The question it answers: why did matching not
// become UNIQUE (a false S-room, a room whose planes do not fit, a missing candidate, or a
// competing hypothesis: the decision on the final S-Graph is printed with each competitor).
// With IS_GRAPHS_EXPLAIN_PLANES set, each S-room's planes (in B) and its A-room's surfaces too,
// and at the end every mapped wall plane in B (with its extent).
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/agraph/agraph_queries.h"
#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/candidate_graph.h"
#include "is_graphs/matching/graph_matcher.h"
#include "is_graphs/matching/room_descriptor.h"
#include "is_graphs/matching/surface_evidence.h"
#include "is_graphs/pipeline/evaluation.h"
#include "is_graphs/sgraph/evaluation.h"

namespace is_graphs {
namespace bag_replay {

inline void ExplainMatch(const agraph::AGraph& building, const sgraph::SGraph& graph,
                         const std::vector<sgraph::StampedPose>& truth,
                         const matching::MatcherConfig& config) {
  const auto traj = sgraph::EvaluateTrajectory(graph, truth);
  const Eigen::Vector3d xi = geometry::ToXYYaw(traj.bim_T_map_gravity);
  matching::Pose2 true_pose;
  true_pose.yaw = xi.z();
  true_pose.t = xi.head<2>();
  // The storey walked (from the truth's height): rooms are looked up on it, hypotheses on
  // another storey are said to be.
  const int true_storey =
      truth.empty() ? -1 : agraph::StoreyAtHeight(building, truth.back().pose.translation().z());
  std::printf("explain: true B_x_M (%.2f, %.2f, %.1f deg) from %d keyframes, storey %d\n", xi.x(),
              xi.y(), xi.z() * 180 / M_PI, traj.keyframes, true_storey);
  const auto a_rooms = matching::DescribeARooms(building);
  const auto s_rooms = matching::DescribeSRooms(graph);
  auto name = [&](int a_index) {
    return a_index < 0 ? std::string("-") : building.rooms[a_rooms[a_index].id].name;
  };
  for (size_t i = 0; i < s_rooms.size(); ++i) {
    const auto& s = s_rooms[i];
    const Eigen::Vector2d c = true_pose.Apply(s.centre);
    int inside = -1;
    double best = 1e9;
    for (size_t j = 0; j < a_rooms.size(); ++j) {
      if (true_storey >= 0 && a_rooms[j].storey != true_storey) continue;
      const double dist = matching::SignedDistanceToPolygon(a_rooms[j].polygon, c);
      if (dist < best) best = dist, inside = static_cast<int>(j);
    }
    std::printf("S-room %d (%s, %zu planes) centre in B (%.2f, %.2f): in %s (%.2f m)", s.id,
                s.kind == matching::RoomKind::kRoom ? "room" : "corridor", s.planes.size(), c.x(),
                c.y(), name(inside).c_str(), best);
    if (inside >= 0) {
      const auto& a = a_rooms[inside];
      const auto e = matching::EvaluatePair(s, a, true_pose, s.kind == matching::RoomKind::kRoom,
                                            matching::EvaluationTolerances::From(config));
      std::printf("; under the truth: %s, %zu/%zu planes paired, rms %.3f m, A-centre %.2f m away",
                  e.ok ? "ok" : "NOT ok", e.surfaces.size(), s.planes.size(), e.rms,
                  (a.centre - c).norm());
    }
    std::printf("\n");
    if (std::getenv("IS_GRAPHS_EXPLAIN_PLANES")) {
      for (const auto& p : s.planes) {
        const Eigen::Vector2d n = true_pose.Rotate(p.normal);
        const double d = p.d + n.dot(true_pose.t);
        std::printf("      plane %d: n (%.2f, %.2f) d %.2f r %.2f length %.2f\n", p.id, n.x(),
                    n.y(), d, p.r, p.length);
      }
      if (inside >= 0)
        for (const auto& p : a_rooms[inside].planes)
          std::printf("      A-surface %d: n (%.2f, %.2f) d %.2f r %.2f length %.2f\n", p.id,
                      p.normal.x(), p.normal.y(), p.d, p.r, p.length);
    }
    for (const auto& cand :
         matching::GenerateRoomCandidates(s, static_cast<int>(i), a_rooms, config)) {
      const double dyaw = geometry::NormalizeAngle(cand.pose.yaw - true_pose.yaw) * 180 / M_PI;
      const double dt = (cand.pose.Apply(s.centre) - c).norm();
      std::printf(
          "    candidate %-14s quality %.2f %s yaw %+6.1f deg, centre %.2f m from the truth\n",
          name(cand.a_room).c_str(), cand.quality, cand.full_rank ? "full" : "axis", dyaw, dt);
    }
  }
  // The decision on this S-Graph: the best hypothesis and those competing with it.
  matching::GraphMatcher matcher(config);
  matcher.SetAGraph(building);
  const matching::GraphMatch m = matcher.Match(graph);
  auto print = [&](const char* what, const Eigen::Isometry3d& pose, double score, int rooms,
                   int storey) {
    const Eigen::Vector3d h = geometry::ToXYYaw(pose);
    const double off = (h.head<2>() - xi.head<2>()).norm();
    std::printf(
        "  %s B_x_M (%.2f, %.2f, %.1f deg) storey %d%s, score %.3f, %d room pairs; %.2f m, "
        "%.1f deg from the truth\n",
        what, h.x(), h.y(), h.z() * 180 / M_PI, storey,
        storey != true_storey && true_storey >= 0 ? " (WRONG storey)" : "", score, rooms, off,
        std::abs(geometry::NormalizeAngle(h.z() - xi.z())) * 180 / M_PI);
  };
  std::printf("match of this S-Graph: %s\n", matching::ToString(m.status));
  // Which wall planes the BIM explains under a motion (SurfaceEvidence: share of each extent).
  const auto walls = matching::WallSegments(graph, config);
  const matching::SurfaceEvidence evidence(building, config);
  auto shares = [&](const Eigen::Isometry3d& pose, int storey) {
    const Eigen::Vector3d h = geometry::ToXYYaw(pose);
    const matching::Pose2 p{h.z(), h.head<2>()};
    std::printf("    wall planes on BIM surfaces:");
    for (const auto& w : walls) std::printf(" %d:%.2f", w.id, evidence.Share(w, p, storey));
    std::printf("\n");
  };
  // The doorways walked through, under the truth: the nearest BIM doorway, and its pair if any.
  for (const auto& d : graph.doorways) {
    const Eigen::Vector2d at = true_pose.Apply(d.position.head<2>());
    const agraph::Doorway* nearest = nullptr;
    for (const auto& a : building.doorways)
      if (true_storey >= 0 && a.storey != true_storey) {
        continue;
      } else if (!nearest ||
                 (a.position.head<2>() - at).norm() < (nearest->position.head<2>() - at).norm())
        nearest = &a;
    std::printf("S-doorway %d (width %.2f m, %zu rooms) in B (%.2f, %.2f)", d.id, d.width,
                d.rooms.size(), at.x(), at.y());
    if (nearest)
      std::printf(": nearest BIM doorway %d '%s' (width %.2f m) %.2f m away", nearest->id,
                  nearest->name.c_str(), nearest->width, (nearest->position.head<2>() - at).norm());
    for (const auto& p : m.doorway_pairs)
      if (p.s_id == d.id) std::printf("; paired with %d (%.2f)", p.a_id, p.score);
    std::printf("\n");
  }
  if (m.status != matching::MatchStatus::kNone) {
    print("best      ", m.bim_T_map, m.score, static_cast<int>(m.room_pairs.size()), m.storey);
    shares(m.bim_T_map, m.storey);
  }
  for (const auto& alt : m.alternatives) {
    print("competitor", alt.bim_T_map, alt.score, alt.rooms, alt.storey);
    shares(alt.bim_T_map, alt.storey);
  }
  if (!std::getenv("IS_GRAPHS_EXPLAIN_PLANES")) return;
  for (const auto& p : graph.planes) {
    if (std::abs(p.plane.normal.z()) > 0.5) continue;  // the floor
    const Eigen::Vector2d n = true_pose.Rotate(p.plane.normal.head<2>().normalized());
    const Eigen::Vector2d a = true_pose.Apply(p.start), b = true_pose.Apply(p.end);
    std::printf("plane %3d: n (%5.2f, %5.2f) from (%6.2f, %6.2f) to (%6.2f, %6.2f), z %.2f..%.2f\n",
                p.id, n.x(), n.y(), a.x(), a.y(), b.x(), b.y(), p.z_min, p.z_max);
  }
}

}  // namespace bag_replay
}  // namespace is_graphs
