#include "is_graphs/merging/merger.h"

#include "is_graphs/agraph/agraph_queries.h"
#include "is_graphs/agraph/agraph_validation.h"
#include "is_graphs/geometry/se3.h"
#include "is_graphs/merging/recent_evidence.h"
#include "is_graphs/merging/room_floors.h"
#include "is_graphs/sgraph/levels.h"

namespace is_graphs {
namespace merging {
namespace {

MatchPairs ToPairs(const matching::GraphMatch& match) {
  MatchPairs pairs;
  for (const auto& p : match.room_pairs) pairs.rooms[p.s_id] = p.a_id;
  for (const auto& p : match.surface_pairs) pairs.surfaces[p.s_id].push_back(p.a_id);
  return pairs;
}

const sgraph::Keyframe* NewestKeyframe(const sgraph::SGraph& g) {
  const sgraph::Keyframe* newest = nullptr;
  for (const auto& k : g.keyframes)
    if (!newest || k.stamp >= newest->stamp) newest = &k;
  return newest;
}

}  // namespace

const char* ToString(MergeEvent event) {
  switch (event) {
    case MergeEvent::kNone:
      return "none";
    case MergeEvent::kLocalized:
      return "localized";
    case MergeEvent::kUpdated:
      return "updated";
    case MergeEvent::kRejected:
      return "rejected";
    case MergeEvent::kLost:
      return "lost";
  }
  return "?";
}

Eigen::Vector2d NewestKeyframePosition(const sgraph::SGraph& s_graph) {
  const sgraph::Keyframe* k = NewestKeyframe(s_graph);
  return k ? Eigen::Vector2d(k->pose.translation().head<2>()) : Eigen::Vector2d::Zero();
}

std::string Merger::SetAGraph(const agraph::AGraph& graph) {
  Reset();
  has_a_graph_ = false;
  const std::string error = agraph::ValidateAGraph(graph);
  if (!error.empty()) return error;
  a_graph_ = graph;
  has_a_graph_ = true;
  return "";
}

void Merger::Reset() {
  merged_ = false;
  pairs_ = MatchPairs();
  deviations_.clear();
}

double Merger::HeightOfMap(const sgraph::SGraph& s_graph, double fallback) const {
  // M's height in B: the storey's floor elevation minus the S-Graph floor's height in M. The
  // storey of the first room pair, else (a match from wall planes alone) of the first surface.
  // With stairs walked, the S-Graph has a floor per level: the paired element's.
  if (s_graph.floors.empty()) return fallback;
  int storey = -1, level = -1;
  double room_floor = 0.0;
  if (!pairs_.rooms.empty()) {
    const auto [s_room, a_room] = *pairs_.rooms.begin();
    if (a_room < 0 || a_room >= static_cast<int>(a_graph_.rooms.size())) return fallback;
    storey = a_graph_.rooms[a_room].storey;
    room_floor = a_graph_.rooms[a_room].z_min;
    for (const auto& r : s_graph.rooms)
      if (r.id == s_room) level = sgraph::LevelOfRoom(s_graph, r);
  } else if (!pairs_.surfaces.empty() && !pairs_.surfaces.begin()->second.empty()) {
    const int a_surface = pairs_.surfaces.begin()->second.front();
    if (a_surface < 0 || a_surface >= static_cast<int>(a_graph_.surfaces.size())) return fallback;
    storey = a_graph_.surfaces[a_surface].storey;
    room_floor = a_graph_.surfaces[a_surface].z_min;
    level = sgraph::LevelOfPlane(s_graph, pairs_.surfaces.begin()->first);
  } else {
    return fallback;
  }
  const double elevation = storey >= 0 && storey < static_cast<int>(a_graph_.storeys.size())
                               ? a_graph_.storeys[storey].elevation
                               : room_floor;
  const sgraph::Floor* floor = &s_graph.floors.front();
  for (const auto& f : s_graph.floors)
    if (f.id == level) floor = &f;
  // Split levels, steps and ramps: the floor of the rooms the robot stood in, when known. The
  // body stands as high above every floor as above the first floor plane (levels.h).
  const double from_storey = elevation - floor->height;
  if (s_graph.keyframes.empty()) return from_storey;
  const double standing =
      s_graph.keyframes.front().pose.translation().z() - s_graph.floors.front().height;
  const auto from_rooms =
      HeightOfMapFromRoomFloors(a_graph_, storey, s_graph, sgraph::HasLevels(s_graph) ? level : -1,
                                xi_, standing, from_storey);
  return from_rooms ? *from_rooms : from_storey;
}

int Merger::StoreyWalked(const sgraph::SGraph& s_graph) const {
  const sgraph::Keyframe* k = NewestKeyframe(s_graph);
  if (!k) return -1;
  return agraph::StoreyAtHeight(a_graph_,
                                HeightOfMap(s_graph, match_z_) + k->pose.translation().z());
}

MergeOutput Merger::OnMatch(const matching::GraphMatch& match, const sgraph::SGraph& s_graph) {
  MergeOutput out;
  if (!has_a_graph_ || match.a_graph_sha256 != a_graph_sha256()) {
    out.message = "match for another A-Graph (" + match.a_graph_sha256 + "): ignored";
    return out;
  }
  if (match.status != matching::MatchStatus::kUnique) {
    if (!merged_) {
      out.message = std::string("match ") + matching::ToString(match.status) + ": not merging";
      return out;
    }
    return OnSGraph(s_graph);
  }
  const Eigen::Vector3d guess = geometry::ToXYYaw(match.bim_T_map);
  if (merged_ && match.storey >= 0) {
    // Floors of one plan: the same x, y and yaw on another storey. The storey the robot walks
    // on follows from the merge and the height walked (stairs); a match elsewhere is ignored.
    const int walked = StoreyWalked(s_graph);
    if (walked >= 0 && walked != match.storey) {
      MergeOutput kept = OnSGraph(s_graph);
      kept.message = "UNIQUE match on storey " + std::to_string(match.storey) +
                     " ignored: the robot walks on storey " + std::to_string(walked) +
                     " (from the merge and the height walked)";
      return kept;
    }
  }
  if (merged_) {
    const TransformJump jump = CompareTransforms(xi_, guess, NewestKeyframePosition(s_graph));
    if (!TransformsAgree(jump, config_)) {
      Reset();
      out.event = MergeEvent::kLost;
      out.message = "a new UNIQUE match contradicts the merge (" +
                    std::to_string(jump.translation) + " m, " + std::to_string(jump.yaw_deg) +
                    " deg apart): merge dropped, matching again";
      return out;
    }
    const MatchPairs fresh = ToPairs(match);
    for (const auto& [s, a] : fresh.rooms) pairs_.rooms[s] = a;
    for (const auto& [s, a] : fresh.surfaces) pairs_.surfaces[s] = a;  // a: the pieces
    prior_ = guess;
    match_z_ = match.bim_T_map.translation().z();
    return SolveAndCheck(s_graph, false);
  }
  pairs_ = ToPairs(match);
  xi_ = guess;
  prior_ = guess;
  match_z_ = match.bim_T_map.translation().z();
  return SolveAndCheck(s_graph, true);
}

MergeOutput Merger::OnSGraph(const sgraph::SGraph& s_graph) {
  if (!merged_) return MergeOutput();
  return SolveAndCheck(s_graph, false);
}

MergeOutput Merger::SolveAndCheck(const sgraph::SGraph& s_graph, bool starting) {
  MergeOutput out;
  const double z = HeightOfMap(s_graph, match_z_);
  out.solution = SolveMerge(a_graph_, s_graph, pairs_, xi_, prior_, z, config_, deviations_);
  out.consistency = CheckConsistency(out.solution, config_, starting);
  out.evidence = CheckRecentEvidence(a_graph_, s_graph, out.solution, config_);
  if (out.consistency.consistent && out.evidence.contradicts) {
    out.consistency.consistent = false;
    out.consistency.message =
        "what the robot sees now contradicts the BIM (kidnapped?): " + out.evidence.message;
  }
  if (!out.consistency.consistent) {
    const bool was_merged = merged_;
    Reset();
    out.event = was_merged ? MergeEvent::kLost : MergeEvent::kRejected;
    out.message = (was_merged ? "merge contradicted, dropped: " : "UNIQUE match rejected: ") +
                  out.consistency.message;
    return out;
  }
  // The outliers of a consistent merge are wrong pairs (or walls moved since the BIM): drop them.
  for (int s : out.consistency.outlier_surfaces) pairs_.surfaces.erase(s);
  for (int s : out.consistency.outlier_rooms) pairs_.rooms.erase(s);
  xi_ = out.solution.bim_x_map;
  deviations_.clear();
  for (const auto& w : out.solution.walls) deviations_[w.wall_id] = {w.offset, w.angle};
  merged_ = true;
  out.merged = true;
  out.event = starting ? MergeEvent::kLocalized : MergeEvent::kUpdated;
  out.bim_T_map = out.solution.BimTMap();
  out.covariance = out.solution.covariance;
  out.bim_T_odom = out.bim_T_map;
  if (const sgraph::Keyframe* k = NewestKeyframe(s_graph)) {
    auto merged = out.solution.keyframes.find(k->id);
    const Eigen::Isometry3d& map_T_k =
        merged != out.solution.keyframes.end() ? merged->second : k->pose;
    // O in B, gravity-aligned (yaw only) and placed so that the keyframe lands where the merge
    // put it. Taking the translation of the full c instead would carry any roll/pitch left
    // between the S-Graph's keyframe and odometry's over the lever arm from O's origin to the
    // robot: 0.5 deg over 30 m walked is 0.26 m in z (seen on AC11's second floor).
    const Eigen::Isometry3d bim_T_k = out.bim_T_map * map_T_k;
    // Never silently a pose above the roof or below the basement (issue 22).
    const std::string outside = agraph::HeightOutsideStoreys(a_graph_, bim_T_k.translation().z());
    if (!outside.empty()) out.warnings.push_back(outside);
    const Eigen::Isometry3d c = bim_T_k * k->odom_pose.inverse();
    const Eigen::Isometry3d yaw_only = geometry::IsometryFromXYYaw(0.0, 0.0, geometry::Yaw(c), 0.0);
    out.bim_T_odom = yaw_only;
    out.bim_T_odom.translation() =
        bim_T_k.translation() - yaw_only.linear() * k->odom_pose.translation();
    out.anchor.odom_T_keyframe = k->odom_pose;
    out.anchor.bim_T_keyframe = out.bim_T_odom * k->odom_pose;
    if (config_.calibrate_odometry)
      out.anchor.calibration = CalibrateOdometry(s_graph, out.solution.keyframes);
  }
  out.message = out.consistency.message;
  return out;
}

}  // namespace merging
}  // namespace is_graphs
