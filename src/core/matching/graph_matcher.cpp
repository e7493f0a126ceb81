// GraphMatcher's entry points: the A-Graph set, and Match, which picks what is matched: the
// S-Graph's current level (not on a stair), against the storeys the levels walked leave possible.
// The match of one level is MatchLevel (graph_matcher_decision.cpp).
#include "is_graphs/matching/graph_matcher.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "is_graphs/matching/input_checks.h"
#include "is_graphs/matching/storeys_walked.h"
#include "is_graphs/sgraph/levels.h"

namespace is_graphs {
namespace matching {

GraphMatcher::GraphMatcher(const MatcherConfig& config) : config_(config) {
  if (config.doubt_centre_tolerance > config.centre_tolerance) {
    MatcherConfig lenient = config;
    lenient.centre_tolerance = config.doubt_centre_tolerance;
    lenient.doubt_centre_tolerance = 0.0;  // the doubter does not doubt itself
    lenient.scan_proposals = false;        // it makes no proposals
    // It pairs rooms through their walls too: without, M2 went UNIQUE on the cellar (the
    // second floor's hall, paired through its walls, was the competitor it found).
    doubter_ = std::make_unique<GraphMatcher>(lenient);
  }
}

std::vector<std::string> GraphMatcher::SetAGraph(const agraph::AGraph& graph) {
  a_rooms_ = DescribeARooms(graph);
  crossings_ = WallCrossings(graph, config_.door_margin, config_.sight_door_margin);
  surfaces_ = SurfaceEvidence(graph, config_);
  doorways_ = DoorwayEvidence(graph, config_);
  a_corners_ = FindCorners(FacingSurfaces(graph), config_.proposal_corner_reach);
  if (config_.scan_proposals) scan_ = ScanSearch(graph, config_.scan_search);
  scan_view_ = ScanView();
  a_sha256_ = graph.source.sha256;
  a_storeys_ = static_cast<int>(graph.storeys.size());
  storey_elevations_.clear();
  for (const agraph::Storey& st : graph.storeys) storey_elevations_[st.id] = st.elevation;
  storeys_walked_.clear();
  level_storeys_.clear();
  has_agraph_ = true;
  cache_.clear();
  last_best_.reset();
  last_checked_.reset();
  if (doubter_) doubter_->SetAGraph(graph);
  return CheckAGraph(graph);
}

GraphMatch GraphMatcher::Match(const sgraph::SGraph& graph) {
  if (sgraph::OnStair(graph, config_.stair_height_tolerance)) {
    const double off = sgraph::HeightOffLevel(graph);
    GraphMatch out;
    out.a_graph_sha256 = a_sha256_;
    out.s_graph_revision = graph.revision;
    std::ostringstream why;
    why.precision(2);
    why << "the robot is " << std::abs(off) << " m " << (off > 0 ? "above" : "below")
        << " the level it walks on (a stair): not matching until it settles on a level";
    out.warnings.push_back(why.str());
    return out;
  }
  storeys_walked_.clear();
  if (doubter_) doubter_->storeys_walked_.clear();
  if (!sgraph::HasLevels(graph)) return Remember(0, MatchLevel(graph));
  const int level = sgraph::CurrentLevel(graph);
  if (level != level_) {
    const std::map<int, int> known = level_storeys_;  // kept over a climb
    ForgetHistory();
    level_storeys_ = known;
    level_ = level;
  }
  if (level != 0 && a_storeys_ == 1) {
    // One storey loaded (the one the robot started on, level 0): the others are not in it.
    GraphMatch out;
    out.a_graph_sha256 = a_sha256_;
    out.s_graph_revision = graph.revision;
    out.warnings.push_back("the robot walks on another level (" + std::to_string(level) +
                           ") than the one it started on, and only one storey is loaded: not "
                           "matching there (load the whole building for runs over stairs)");
    return out;
  }
  // The heights walked between levels rule out storeys without one as far above or below.
  // Level -> its height in M: its floor's where every level has one (a level moved off a
  // landing has its first keyframes on the landing), else its first keyframe's.
  std::map<int, double> heights, floors;
  for (const auto& k : graph.keyframes) heights.try_emplace(k.level, k.pose.translation().z());
  for (const auto& f : graph.floors) floors[f.id] = f.height;
  if (std::all_of(heights.begin(), heights.end(),
                  [&](const auto& h) { return floors.count(h.first) > 0; })) {
    for (auto& [l, h] : heights) h = floors[l];
  }
  // A level whose storey a UNIQUE match named fixes the others by the heights between; else
  // the heights between the levels alone rule out storeys without one as far above or below.
  const std::optional<std::vector<int>> from_known =
      StoreysFromKnownLevels(storey_elevations_, heights, level_storeys_, level,
                             config_.storey_level_tolerance, config_.storey_level_tolerance_per_m);
  if (from_known && from_known->empty()) {
    GraphMatch out;
    out.a_graph_sha256 = a_sha256_;
    out.s_graph_revision = graph.revision;
    out.warnings.push_back("level " + std::to_string(level) +
                           " lies where no storey of the building is, from the storeys matched "
                           "on the levels walked before (a landing, or off the building's "
                           "storeys): not matching there");
    return out;
  }
  if (from_known) storeys_walked_ = *from_known;
  if (storeys_walked_.empty()) {
    storeys_walked_ =
        StoreysFittingLevels(storey_elevations_, heights, level, config_.storey_level_tolerance,
                             config_.storey_level_tolerance_per_m);
  }
  if (doubter_) doubter_->storeys_walked_ = storeys_walked_;
  return Remember(level, MatchLevel(sgraph::LevelSubgraph(graph, level)));
}

GraphMatch GraphMatcher::Remember(int level, GraphMatch match) {
  if (match.status == MatchStatus::kUnique && match.storey >= 0)
    level_storeys_[level] = match.storey;
  return match;
}

}  // namespace matching
}  // namespace is_graphs
