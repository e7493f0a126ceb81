// The pairs of a hypothesis as the answer reports them (room pairs, surface pairs) and as the
// doorway evidence looks them up (S-room id -> A-room id).
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "is_graphs/matching/graph_matcher.h"

namespace is_graphs {
namespace matching {

std::vector<MatchPair> GraphMatcher::RoomPairs(const Hypothesis& h,
                                               const std::vector<RoomDescriptor>& s_rooms) const {
  // Only pairs whose centres correspond as the merge takes them: a room's centre to the
  // A-centre, a corridor's across its axis. Not a room paired through its planes only
  // (centre_off: a plane standing in it moved the S-centre), nor an S-Graph room paired along
  // one direction only (its centre free along it: a corridor's end taken for a room's wall).
  // Their surfaces are paired all the same.
  std::vector<MatchPair> out;
  for (const auto& m : h.members)
    if (!m.evaluation.centre_off && (m.full_rank || s_rooms[m.s_room].kind == RoomKind::kCorridor))
      out.push_back({a_rooms_[m.a_room].id, s_rooms[m.s_room].id, m.evaluation.quality});
  std::sort(out.begin(), out.end(),
            [](const MatchPair& x, const MatchPair& y) { return x.s_id < y.s_id; });
  return out;
}

std::vector<MatchPair> GraphMatcher::SurfacePairs(
    const Hypothesis& h, const std::vector<RoomDescriptor>& s_rooms) const {
  // By S-plane id: the best pair's score and A-feature; every piece of the feature is paired
  // (an S-plane along collinear A-surfaces pairs with each of them).
  std::map<int, std::pair<double, const PlaneFeature*>> surfaces;
  for (const auto& m : h.members) {
    const RoomDescriptor& s = s_rooms[m.s_room];
    const RoomDescriptor& a = a_rooms_[m.a_room];
    for (size_t k = 0; k < m.evaluation.surfaces.size(); ++k) {
      const auto [i, j] = m.evaluation.surfaces[k];
      const double r = m.evaluation.residuals[k] / config_.quality_sigma;
      const double score = std::exp(-0.5 * r * r);
      auto it = surfaces.find(s.planes[i].id);
      if (it == surfaces.end() || it->second.first < score)
        surfaces[s.planes[i].id] = {score, &a.planes[j]};
    }
  }
  std::vector<MatchPair> out;
  for (const auto& [s_id, best_pair] : surfaces) {
    std::vector<int> pieces = best_pair.second->pieces;
    if (pieces.empty()) pieces = {best_pair.second->id};
    std::sort(pieces.begin(), pieces.end());
    for (int a_id : pieces) out.push_back({a_id, s_id, best_pair.first});
  }
  return out;
}

std::map<int, int> GraphMatcher::PairedRooms(const Hypothesis& h,
                                             const std::vector<RoomDescriptor>& s_rooms) const {
  std::map<int, int> out;
  for (const auto& m : h.members) out[s_rooms[m.s_room].id] = a_rooms_[m.a_room].id;
  return out;
}

}  // namespace matching
}  // namespace is_graphs
