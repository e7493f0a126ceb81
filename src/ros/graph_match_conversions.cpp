#include "graph_match_conversions.h"

#include "pose_conversions.h"

namespace is_graphs {
namespace ros_conversions {
namespace {

std::vector<is_graphs::MatchPair> PairsToMsg(const std::vector<matching::MatchPair>& pairs) {
  std::vector<is_graphs::MatchPair> out;
  for (const auto& p : pairs) {
    is_graphs::MatchPair m;
    m.a_id = static_cast<uint32_t>(p.a_id);
    m.s_id = static_cast<uint32_t>(p.s_id);
    m.score = p.score;
    out.push_back(m);
  }
  return out;
}

std::vector<matching::MatchPair> PairsFromMsg(const std::vector<is_graphs::MatchPair>& pairs) {
  std::vector<matching::MatchPair> out;
  for (const auto& m : pairs)
    out.push_back({static_cast<int>(m.a_id), static_cast<int>(m.s_id), m.score});
  return out;
}

std::vector<is_graphs::SurfaceDeviation> DeviationsToMsg(
    const std::vector<matching::SurfaceDeviation>& deviations) {
  std::vector<is_graphs::SurfaceDeviation> out;
  for (const auto& d : deviations) {
    is_graphs::SurfaceDeviation m;
    m.a_id = static_cast<uint32_t>(d.a_id);
    m.s_id = static_cast<uint32_t>(d.s_id);
    m.offset = d.offset;
    m.angle = d.angle;
    m.paired = d.paired;
    out.push_back(m);
  }
  return out;
}

std::vector<matching::SurfaceDeviation> DeviationsFromMsg(
    const std::vector<is_graphs::SurfaceDeviation>& deviations) {
  std::vector<matching::SurfaceDeviation> out;
  for (const auto& m : deviations)
    out.push_back({static_cast<int>(m.a_id), static_cast<int>(m.s_id), m.offset, m.angle,
                   static_cast<bool>(m.paired)});
  return out;
}

}  // namespace

is_graphs::GraphMatch ToMsg(const matching::GraphMatch& match) {
  is_graphs::GraphMatch msg;
  msg.status = static_cast<uint8_t>(match.status);
  msg.a_graph_sha256 = match.a_graph_sha256;
  msg.s_graph_revision = match.s_graph_revision;
  msg.room_pairs = PairsToMsg(match.room_pairs);
  msg.surface_pairs = PairsToMsg(match.surface_pairs);
  msg.doorway_pairs = PairsToMsg(match.doorway_pairs);
  msg.deviations = DeviationsToMsg(match.deviations);
  msg.score = match.score;
  msg.hypotheses = match.hypotheses;
  msg.bim_T_map = ToPose(match.bim_T_map);
  msg.storey_id = match.storey;
  msg.competing_storey_ids.assign(match.competing_storeys.begin(), match.competing_storeys.end());
  msg.hint = match.hint;
  msg.scan_set = match.scan_set;
  msg.scan_margin = match.scan_margin;
  msg.scan_search = match.scan_search;
  return msg;
}

matching::GraphMatch FromMsg(const is_graphs::GraphMatch& msg) {
  matching::GraphMatch match;
  switch (msg.status) {
    case is_graphs::GraphMatch::UNIQUE:
      match.status = matching::MatchStatus::kUnique;
      break;
    case is_graphs::GraphMatch::AMBIGUOUS:
      match.status = matching::MatchStatus::kAmbiguous;
      break;
    default:
      match.status = matching::MatchStatus::kNone;
      break;
  }
  match.a_graph_sha256 = msg.a_graph_sha256;
  match.s_graph_revision = msg.s_graph_revision;
  match.room_pairs = PairsFromMsg(msg.room_pairs);
  match.surface_pairs = PairsFromMsg(msg.surface_pairs);
  match.doorway_pairs = PairsFromMsg(msg.doorway_pairs);
  match.deviations = DeviationsFromMsg(msg.deviations);
  match.score = msg.score;
  match.hypotheses = msg.hypotheses;
  match.bim_T_map = FromPose(msg.bim_T_map);
  match.storey = msg.storey_id;
  match.competing_storeys.assign(msg.competing_storey_ids.begin(), msg.competing_storey_ids.end());
  match.hint = msg.hint;
  match.scan_set = msg.scan_set;
  match.scan_margin = msg.scan_margin;
  match.scan_search = msg.scan_search;
  return match;
}

}  // namespace ros_conversions
}  // namespace is_graphs
