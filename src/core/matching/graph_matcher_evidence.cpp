// Step 3 of GraphMatcher::Match: each hypothesis scored on its room pairs and on what the
// S-Graph shows beyond them (loose wall planes, walls outside the building, doorways walked
// through, walls the walked path crosses, planes that could not have been seen).
#include <map>
#include <set>
#include <vector>

#include "is_graphs/matching/graph_matcher.h"

namespace is_graphs {
namespace matching {

std::vector<WallSegment> GraphMatcher::LooseWalls(const sgraph::SGraph& graph,
                                                  const std::vector<WallSegment>& walls,
                                                  const std::vector<RoomDescriptor>& s_rooms,
                                                  const std::vector<Hypothesis>& hypotheses) const {
  if (config_.surface_evidence_weight <= 0.0) return {};
  // The wall planes of no S-room, and of S-rooms no hypothesis pairs (a room whose wall was
  // built off the plan, or whose centre clutter moved out of the gate): the same set for every
  // hypothesis. (A paired room's planes are weighed by its pair. Counting all planes let the
  // partial fits of a mirror image pull apart on planes their pairs already weigh; counting
  // those of the rooms a hypothesis leaves unpaired rewarded pairing fewer: both were tried,
  // both gave wrong UNIQUE answers.)
  std::set<int> paired;  // S-room ids some hypothesis pairs
  for (const auto& h : hypotheses)
    for (const auto& m : h.members) paired.insert(s_rooms[m.s_room].id);
  std::set<int> in_paired_rooms;
  for (const auto& room : graph.rooms)
    if (paired.count(room.id)) in_paired_rooms.insert(room.planes.begin(), room.planes.end());
  std::vector<WallSegment> loose;
  for (const auto& w : walls)
    if (!in_paired_rooms.count(w.id)) loose.push_back(w);
  return loose;
}

double GraphMatcher::Hidden(const Hypothesis& h, const Evidence& evidence) const {
  if (evidence.seen.empty() || config_.sight_penalty <= 0.0) return 0.0;
  return config_.sight_penalty *
         HiddenWalls(evidence.seen, crossings_, h.pose, h.storey, config_.surface_full_length);
}

void GraphMatcher::Score(std::vector<Hypothesis>& hypotheses, const Evidence& evidence,
                         const std::vector<RoomDescriptor>& s_rooms) const {
  // 3. Scores: the pairs' affinity, plus the loose wall planes and the walked-through doorways
  // the BIM explains, less the walls the walked path crosses and the loose planes it could not
  // have seen under each motion and those it puts outside the building. The doorways (each pair
  // adds at most doorway_evidence_weight), the crossings and the sight lines only for the
  // hypotheses that can still matter.
  const bool outside = evidence.outside && config_.outside_penalty > 0.0;
  for (auto& h : hypotheses)
    h.outside = outside && !h.members.empty() && !evidence.loose.empty()
                    ? config_.outside_penalty * surfaces_.Outside(evidence.loose, h.pose, h.storey)
                    : 0.0;
  ScoreHypotheses(
      hypotheses,
      [&](const Hypothesis& h) {
        return evidence.loose.empty()
                   ? 0.0
                   : config_.surface_evidence_weight *
                             surfaces_.Explained(evidence.loose, h.pose, h.storey) -
                         h.outside;
      },
      [&](const Hypothesis& h) { return DoorsExplained(h, evidence, s_rooms); },
      DoorsBound(evidence),
      [&](const Hypothesis& h) { return crossings_.Count(evidence.path, h.pose, h.storey); },
      [&](const Hypothesis& h) { return Hidden(h, evidence); }, config_);
}

double GraphMatcher::DoorsExplained(const Hypothesis& h, const Evidence& evidence,
                                    const std::vector<RoomDescriptor>& s_rooms) const {
  if (evidence.doors.empty() || config_.doorway_evidence_weight <= 0.0) return 0.0;
  return config_.doorway_evidence_weight *
         doorways_.Explained(evidence.doors, h.pose, h.storey, PairedRooms(h, s_rooms));
}

double GraphMatcher::DoorsBound(const Evidence& evidence) const {
  return config_.doorway_evidence_weight > 0.0
             ? config_.doorway_evidence_weight * static_cast<double>(evidence.doors.size())
             : 0.0;
}

}  // namespace matching
}  // namespace is_graphs
