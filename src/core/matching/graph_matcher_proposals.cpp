// Step 6 of GraphMatcher::Match: proposals from the first scans (issue 25). Before a room is
// closed, the wall planes seen so far already fix the motion where they are unique in the
// building: corners of them, paired with the BIM's corners, propose motions; every wall plane,
// the walked path and the sight lines decide between them.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "is_graphs/matching/graph_matcher.h"

namespace is_graphs {
namespace matching {
namespace {

constexpr double kCollinear = 0.05;  // m between the offsets of pieces of one face

}  // namespace

Pose2 GraphMatcher::Refine(const std::vector<WallSegment>& walls, const Pose2& pose,
                           int storey) const {
  std::vector<PlaneCorrespondence> planes;
  for (const WallSegment& w : walls) {
    const auto along = surfaces_.AlongSurfaces(w, pose, storey);
    if (along.empty()) continue;
    // The A-surface it lies along longest; the plane weighed once.
    const auto best = std::max_element(
        along.begin(), along.end(),
        [](const auto& x, const auto& y) { return x.to - x.from < y.to - y.from; });
    PlaneCorrespondence c;
    c.s_normal = w.normal;
    c.s_d = w.normal.dot(0.5 * (w.a + w.b));
    c.a_normal = best->normal;
    c.a_d = best->d;
    c.a_ref = best->middle;
    planes.push_back(c);
  }
  const RigidFit fit = FitYawTranslation(planes, {});
  return fit.translation_determined && fit.planes_determine_translation ? fit.pose : pose;
}

GraphMatcher::ProposalDecision GraphMatcher::Propose(const sgraph::SGraph& graph,
                                                     const Evidence& evidence,
                                                     const std::vector<Hypothesis>& hypotheses,
                                                     bool hypotheses_if_too_many) const {
  ProposalDecision out;
  out.walls = evidence.walls;
  double seen = 0.0;  // walls seen, a plane surface_full_length long counting 1
  for (const auto& w : out.walls) seen += std::min(1.0, w.length / config_.surface_full_length);
  if (seen < config_.proposal_min_walls || a_corners_.empty()) return out;
  const std::vector<Corner> corners =
      FindCorners(FacingWalls(out.walls), config_.proposal_corner_reach);
  bool too_many = false;
  std::vector<MotionProposal> proposals = ProposeMotions(
      corners, a_corners_, config_.angle_tolerance_deg, config_.proposal_max_candidates, &too_many);
  if (too_many) proposals.clear();
  proposals.erase(std::remove_if(proposals.begin(), proposals.end(),
                                 [&](const MotionProposal& p) {
                                   return !StoreyWalkable(p.storey) || !InGate(p.pose, p.storey);
                                 }),
                  proposals.end());
  for (const auto& h : hypotheses)
    if (!h.members.empty()) proposals.push_back({h.pose, h.storey, 0});
  // The poses the scans cannot tell apart (SearchScans, run by the caller).
  if (scan_view_.certified)
    for (const ScanPoseOn& p : scan_view_.set)
      if (InGate(p.pose, p.storey)) proposals.push_back({p.pose, p.storey, 0});
  // What is seen fits too many places to weigh them all: undecided (or, to check the room
  // hypotheses against the walls, only their motions weighed).
  if (too_many && (!hypotheses_if_too_many || proposals.empty())) {
    out.status = MatchStatus::kAmbiguous;
    out.candidates = config_.proposal_max_candidates + 1;
    return out;
  }
  out.candidates = static_cast<int>(proposals.size());
  if (proposals.empty()) return out;
  out.status = MatchStatus::kAmbiguous;
  if (out.candidates > config_.proposal_max_candidates) return out;

  // Every candidate refitted to the planes it puts on A-surfaces (a corner off by a moved wall
  // or noise proposes a motion off by as much) and weighed on the planes alone, best first.
  std::vector<Hypothesis> scored(proposals.size());
  for (size_t i = 0; i < proposals.size(); ++i) {
    Hypothesis& h = scored[i];
    h.storey = proposals[i].storey;
    h.pose = Refine(out.walls, Refine(out.walls, proposals[i].pose, h.storey), h.storey);
    h.evidence = surfaces_.Explained(out.walls, h.pose, h.storey);
  }
  std::stable_sort(scored.begin(), scored.end(), [](const Hypothesis& x, const Hypothesis& y) {
    return x.evidence > y.evidence;
  });
  const double margin = std::max(config_.proposal_margin, config_.proposal_margin_share * seen);
  // Penalised best first, while a candidate can still reach the best cluster.
  std::vector<SeenWall> sight;
  if (config_.sight_penalty > 0.0) sight = SeenFrom(graph, out.walls, config_.sight_viewpoints);
  std::vector<Eigen::Vector2d> points;
  for (const auto& w : out.walls) points.push_back(0.5 * (w.a + w.b));
  std::vector<Hypothesis> full;
  double best_score = -1e18;
  for (Hypothesis& h : scored) {
    if (h.evidence < best_score - margin) break;
    h.crossings = crossings_.Count(evidence.path, h.pose, h.storey);
    h.hidden = sight.empty()
                   ? 0.0
                   : HiddenWalls(sight, crossings_, h.pose, h.storey, config_.surface_full_length);
    h.score = h.evidence - config_.proposal_crossing_penalty * h.crossings - h.hidden;
    best_score = std::max(best_score, h.score);
    full.push_back(h);
  }
  std::stable_sort(full.begin(), full.end(),
                   [](const Hypothesis& x, const Hypothesis& y) { return x.score > y.score; });
  out.best = full.front();
  out.scored = true;
  for (size_t i = 1; i < full.size(); ++i) {
    const Hypothesis& h = full[i];
    if (h.score < out.best.score - margin) break;
    if (h.storey == out.best.storey && SameMotion(out.best.pose, h.pose, points, config_)) continue;
    out.competitors.push_back(h);
  }
  // Motions that put clearly more of the walls seen on BIM walls than the best, though they
  // lose on what contradicts them (a walk through a wall: an opening the plan lacks).
  for (const Hypothesis& h : full)
    if (h.evidence >= out.best.evidence + config_.proposal_margin &&
        !(h.storey == out.best.storey && SameMotion(out.best.pose, h.pose, points, config_)))
      out.more_walls.push_back(h);
  // Motions the scans put more than their margin below the best are out (they cannot be the
  // truth unless the scans' best is wrong too, and then the best below is not in their set).
  bool scans_agree = true;
  if (scan_view_.certified) {
    auto outside = [&](const Hypothesis& h) { return !InScanSet(h, points); };
    out.competitors.erase(
        std::remove_if(out.competitors.begin(), out.competitors.end(), outside),
        out.competitors.end());
    out.more_walls.erase(std::remove_if(out.more_walls.begin(), out.more_walls.end(), outside),
                         out.more_walls.end());
    scans_agree = !outside(out.best);
  }
  const bool enough = out.best.evidence >= config_.proposal_min_share * seen;
  if (enough && out.best.crossings == 0 && out.competitors.empty() && !too_many && scans_agree)
    out.status = MatchStatus::kUnique;
  return out;
}

bool GraphMatcher::WallsPreferAnother(const ProposalDecision& proposed,
                                      const Hypothesis& best) const {
  if (!proposed.scored) return false;  // too little seen, or too many motions to weigh
  std::vector<Eigen::Vector2d> points;
  for (const auto& w : proposed.walls) points.push_back(0.5 * (w.a + w.b));
  auto same = [&](const Hypothesis& h) {
    return h.storey == best.storey && SameMotion(h.pose, best.pose, points, config_);
  };
  // Another motion puts clearly more of the walls seen on BIM walls: evidence against `best`
  // that its score (which counts the walk through walls against the other) hides.
  if (!proposed.more_walls.empty()) {
    const double best_walls = surfaces_.Explained(proposed.walls, best.pose, best.storey);
    for (const Hypothesis& h : proposed.more_walls)
      if (!same(h) && h.evidence >= best_walls + config_.proposal_margin) return true;
  }
  // The rooms' best is among the walls' best cluster: they agree (or the walls cannot tell).
  if (same(proposed.best)) return false;
  for (const Hypothesis& c : proposed.competitors)
    if (same(c)) return false;
  return true;
}

void GraphMatcher::FillFromProposal(const ProposalDecision& proposed,
                                    const std::vector<Hypothesis>& hypotheses,
                                    const std::vector<RoomDescriptor>& s_rooms,
                                    const Evidence& evidence, GraphMatch* out) {
  const Hypothesis& best = proposed.best;
  out->status = MatchStatus::kUnique;
  out->score = best.score;
  out->hypotheses = 1;
  out->bim_T_map = best.pose.ToIsometry();
  out->storey = best.storey;
  last_best_ = best.pose;
  std::vector<Eigen::Vector2d> points;
  for (const auto& w : proposed.walls) points.push_back(0.5 * (w.a + w.b));
  // The room pairs of the best-scoring room hypothesis of the same motion, if any.
  const Hypothesis* rooms = nullptr;
  for (const auto& h : hypotheses)
    if (!h.members.empty() && h.storey == best.storey &&
        SameMotion(h.pose, best.pose, points, config_) && (!rooms || h.score > rooms->score))
      rooms = &h;
  if (rooms) {
    out->room_pairs = RoomPairs(*rooms, s_rooms);
    for (const MatchPair& p : SurfacePairs(*rooms, s_rooms)) out->surface_pairs.push_back(p);
    out->deviations = Deviations(*rooms, s_rooms);
  }
  std::set<int> paired;
  for (const MatchPair& p : out->surface_pairs) paired.insert(p.s_id);
  // Every other wall plane with most of it along A-surfaces under the proposal: each of them.
  for (const WallSegment& w : proposed.walls) {
    if (paired.count(w.id)) continue;
    const double share = surfaces_.Share(w, best.pose, best.storey);
    if (share < 0.5) continue;
    // The A-surface it lies along longest, and those collinear with it (pieces of one face): a
    // nearby parallel face (a recess, a column's face) would pull it off.
    const auto along = surfaces_.AlongSurfaces(w, best.pose, best.storey);
    if (along.empty()) continue;
    const auto longest = std::max_element(
        along.begin(), along.end(),
        [](const auto& x, const auto& y) { return x.to - x.from < y.to - y.from; });
    std::vector<int> ids;
    for (const auto& a : along)
      if (std::abs(a.d - longest->d) <= kCollinear && a.normal.dot(longest->normal) > 0.999)
        ids.push_back(a.id);
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    for (int id : ids) out->surface_pairs.push_back({id, w.id, share});
  }
  out->doorway_pairs = doorways_.Pairs(evidence.doors, best.pose, best.storey,
                                       rooms ? PairedRooms(*rooms, s_rooms) : std::map<int, int>());
  for (const auto& c : proposed.competitors)
    out->alternatives.push_back({c.pose.ToIsometry(), c.score, 0, c.storey});
}

}  // namespace matching
}  // namespace is_graphs
