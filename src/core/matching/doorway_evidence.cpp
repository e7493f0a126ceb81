#include "is_graphs/matching/doorway_evidence.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace is_graphs {
namespace matching {

std::vector<SDoorwayView> UsableDoorways(const sgraph::SGraph& graph,
                                         std::vector<std::string>* warnings) {
  std::vector<SDoorwayView> out;
  if (graph.doorways.empty()) return out;
  const std::string rev = "S-Graph rev " + std::to_string(graph.revision);
  auto warn = [&](const std::string& w) {
    if (warnings) warnings->push_back(w);
  };
  if (graph.rooms.empty()) {
    warn(rev + ": " + std::to_string(graph.doorways.size()) +
         " doorways but no rooms (doorways ignored)");
    return out;
  }
  std::set<int> room_ids;
  for (const auto& r : graph.rooms) room_ids.insert(r.id);
  for (const auto& d : graph.doorways) {
    const std::string name = rev + ": doorway " + std::to_string(d.id);
    if (!d.position.allFinite() || !std::isfinite(d.width) || d.width < 0.0) {
      warn(name + ": non-finite position or width (ignored)");
      continue;
    }
    const auto unknown =
        std::find_if(d.rooms.begin(), d.rooms.end(), [&](int r) { return !room_ids.count(r); });
    if (unknown != d.rooms.end()) {
      warn(name + ": names room " + std::to_string(*unknown) + " which does not exist (ignored)");
      continue;
    }
    if (d.rooms.empty()) {
      warn(name + ": between no rooms (ignored)");
      continue;
    }
    out.push_back({d.id, d.position.head<2>(), d.width, d.rooms});
  }
  return out;
}

namespace {

long long CellKey(long long ix, long long iy) { return (ix << 32) ^ (iy & 0xffffffffLL); }

}  // namespace

DoorwayEvidence::DoorwayEvidence(const agraph::AGraph& graph, const MatcherConfig& config)
    : tolerance_(config.doorway_tolerance),
      width_tolerance_(config.doorway_width_tolerance),
      cell_(std::max(1.0, config.doorway_tolerance)) {
  for (const auto& d : graph.doorways) {
    // The S-Graph finds a doorway where the walk goes through a wall plane: never at a virtual
    // separation (no wall there).
    if (!d.InWall() || !d.position.allFinite() || !std::isfinite(d.width)) continue;
    Storey& st = storeys_[d.storey];
    const Eigen::Vector2d at = d.position.head<2>();
    st.cells[CellKey(static_cast<long long>(std::floor(at.x() / cell_)),
                     static_cast<long long>(std::floor(at.y() / cell_)))]
        .push_back(static_cast<int>(st.doors.size()));
    st.doors.push_back({d.id, at, d.width, d.rooms});
  }
}

std::vector<MatchPair> DoorwayEvidence::Pairs(const std::vector<SDoorwayView>& doorways,
                                              const Pose2& pose, int storey,
                                              const std::map<int, int>& s_to_a_room) const {
  const auto it = storeys_.find(storey);
  if (doorways.empty() || it == storeys_.end()) return {};
  struct Candidate {
    double distance;
    int s, a;  // indices
  };
  std::vector<Candidate> candidates;
  const Storey& st = it->second;
  std::vector<int> near;
  const Eigen::Matrix2d rot = pose.R();  // once, not per doorway
  for (size_t i = 0; i < doorways.size(); ++i) {
    const SDoorwayView& s = doorways[i];
    const Eigen::Vector2d at = rot * s.at + pose.t;
    // The A-doorways in the 3 x 3 cells around it, in index order (deterministic pairing).
    near.clear();
    const long long cx = static_cast<long long>(std::floor(at.x() / cell_));
    const long long cy = static_cast<long long>(std::floor(at.y() / cell_));
    for (long long ix = cx - 1; ix <= cx + 1; ++ix)
      for (long long iy = cy - 1; iy <= cy + 1; ++iy) {
        const auto cell = st.cells.find(CellKey(ix, iy));
        if (cell != st.cells.end())
          near.insert(near.end(), cell->second.begin(), cell->second.end());
      }
    std::sort(near.begin(), near.end());
    for (int j : near) {
      const Door& a = st.doors[j];
      const double distance = (a.at - at).norm();
      if (distance > tolerance_) continue;
      if (s.width > 0.0 && a.width > 0.0 && std::abs(s.width - a.width) > width_tolerance_)
        continue;
      const bool rooms_agree = std::all_of(s.rooms.begin(), s.rooms.end(), [&](int r) {
        const auto paired = s_to_a_room.find(r);
        return paired == s_to_a_room.end() ||
               std::count(a.rooms.begin(), a.rooms.end(), paired->second) > 0;
      });
      if (rooms_agree) candidates.push_back({distance, static_cast<int>(i), j});
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& x, const Candidate& y) { return x.distance < y.distance; });
  std::vector<bool> s_used(doorways.size(), false), a_used(st.doors.size(), false);
  std::vector<MatchPair> out;
  const double sigma = 0.5 * tolerance_;
  for (const auto& c : candidates) {
    if (s_used[c.s] || a_used[c.a]) continue;
    s_used[c.s] = a_used[c.a] = true;
    const double r = c.distance / sigma;
    out.push_back({st.doors[c.a].id, doorways[c.s].id, std::exp(-0.5 * r * r)});
  }
  return out;
}

double DoorwayEvidence::Explained(const std::vector<SDoorwayView>& doorways, const Pose2& pose,
                                  int storey, const std::map<int, int>& s_to_a_room) const {
  double sum = 0.0;
  for (const auto& p : Pairs(doorways, pose, storey, s_to_a_room)) sum += p.score;
  return sum;
}

}  // namespace matching
}  // namespace is_graphs
