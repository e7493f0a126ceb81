// Steps 4-6 of GraphMatcher::Match on one level: the hypotheses decided on their scores and the
// margin, a UNIQUE answer doubted, cross-checked against the wall planes seen and gated on the
// share of them it fits; the answer filled in.
#include <algorithm>
#include <chrono>
#include <optional>
#include <sstream>
#include <vector>

#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/graph_matcher.h"
#include "is_graphs/matching/input_checks.h"

namespace is_graphs {
namespace matching {

void GraphMatcher::GateOnWallsSeen(const std::vector<WallSegment>& walls, GraphMatch* out) const {
  if (out->status != MatchStatus::kUnique || config_.unique_min_wall_share <= 0.0) return;
  const double bound = surfaces_.Bound(walls);
  if (bound < config_.unique_min_walls) return;
  const Eigen::Vector3d xi = geometry::ToXYYaw(out->bim_T_map);
  const double share = surfaces_.Explained(walls, Pose2{xi.z(), xi.head<2>()}, out->storey) / bound;
  if (share >= config_.unique_min_wall_share) return;
  out->status = MatchStatus::kAmbiguous;
  std::ostringstream why;
  why.precision(2);
  why << "the best hypothesis fits only " << share << " of the walls seen (< "
      << config_.unique_min_wall_share << "): not UNIQUE";
  out->warnings.push_back(why.str());
}

GraphMatch GraphMatcher::MatchLevel(const sgraph::SGraph& graph) {
  const auto t0 = std::chrono::steady_clock::now();
  stats_ = MatchStats{};
  GraphMatch out;
  out.a_graph_sha256 = a_sha256_;
  out.s_graph_revision = graph.revision;
  out.warnings = CheckSGraph(graph);
  const std::vector<RoomDescriptor> s_rooms = DescribeSRooms(graph);
  stats_.s_rooms = static_cast<int>(s_rooms.size());
  if (a_rooms_.empty()) out.warnings.push_back("no A-Graph rooms with surfaces to match against");
  // No S-room yet is the normal start (the proposals work on the wall planes); S-rooms none of
  // which is usable are not.
  if (s_rooms.empty() && !graph.rooms.empty())
    out.warnings.push_back("no S-Graph rooms with usable planes to match");
  if (a_rooms_.empty()) return out;

  std::vector<Hypothesis> hypotheses =
      s_rooms.empty() ? std::vector<Hypothesis>() : Hypothesize(s_rooms);
  // One set of loose wall planes for this S-Graph, the doubter's hypotheses scored on it too.
  Evidence evidence;
  evidence.walls = WallSegments(graph, config_);
  evidence.loose = LooseWalls(graph, evidence.walls, s_rooms, hypotheses);
  evidence.path = WalkedPath(graph, config_.max_path_step);
  evidence.doors = UsableDoorways(graph, &out.warnings);
  if (config_.sight_penalty > 0.0 && !s_rooms.empty())
    evidence.seen = SeenFrom(graph, evidence.loose, config_.sight_viewpoints);
  Score(hypotheses, evidence, s_rooms);
  std::vector<Eigen::Vector2d> s_points;
  for (const auto& s : s_rooms) s_points.push_back(s.centre);

  // 4. Decision; 5. a UNIQUE one doubted. Walls outside the building count against the others
  // only for a best that puts none there itself: a best they contradict too is decided on the
  // rest of the evidence alone (the walls outside may be the truth's: seen through a window, an
  // annex not in the plan; and dropping a competitor for them must not leave a wrong best).
  Decision decision = Decide(hypotheses, s_points, static_cast<int>(s_rooms.size()), config_);
  if (decision.best >= 0 && hypotheses[decision.best].outside > 0.0) {
    evidence.outside = false;
    Score(hypotheses, evidence, s_rooms);
    decision = Decide(hypotheses, s_points, static_cast<int>(s_rooms.size()), config_);
  }
  stats_.hypotheses = static_cast<int>(hypotheses.size());
  std::optional<Hypothesis> doubt;
  if (decision.status == MatchStatus::kUnique && doubter_) {
    doubt = Doubt(s_rooms, hypotheses[decision.best], s_points, evidence);
    if (doubt) decision.status = MatchStatus::kAmbiguous;
  }
  // 5b. A UNIQUE answer from the rooms checked against every wall plane seen (the proposals):
  // where the walls clearly prefer another motion, the two kinds of evidence disagree and
  // neither is taken (AMBIGUOUS, the walls' best its competitor).
  // Checked once per motion: a UNIQUE answer of the motion checked last is not checked again
  // (the proposals cost 5-100x the rooms' matching; the merger watches a localized motion);
  // and only where few rooms are paired (proposal_cross_check_max_rooms).
  std::optional<ProposalDecision> walls_view;
  bool scan_searched = false;
  if (decision.status == MatchStatus::kUnique && config_.proposals &&
      config_.proposal_cross_check &&
      hypotheses[decision.best].rooms <= config_.proposal_cross_check_max_rooms &&
      !(last_checked_ &&
        SameMotion(*last_checked_, hypotheses[decision.best].pose, s_points, config_))) {
    SearchScans(graph);
    scan_searched = true;
    walls_view = Propose(graph, evidence, hypotheses, /*hypotheses_if_too_many=*/true);
    if (WallsPreferAnother(*walls_view, hypotheses[decision.best])) {
      decision.status = MatchStatus::kAmbiguous;
      last_checked_.reset();
      out.warnings.push_back(
          "the room pairs' best motion and the wall planes' best disagree: not UNIQUE");
    } else {
      last_checked_ = hypotheses[decision.best].pose;
    }
  }
  // 6. Without a UNIQUE answer from the rooms: the proposals, on every wall plane seen.
  if (decision.status != MatchStatus::kUnique && config_.proposals) {
    if (!walls_view) {
      SearchScans(graph);
      scan_searched = true;
    }
    ProposalDecision proposed = walls_view ? *walls_view : Propose(graph, evidence, hypotheses);
    if (walls_view) proposed.status = MatchStatus::kAmbiguous;  // the rooms say otherwise
    stats_.proposals = proposed.candidates;
    if (proposed.status == MatchStatus::kUnique) {
      FillFromProposal(proposed, hypotheses, s_rooms, evidence, &out);
      FillScanSearch(&out);
      out.competing_storeys = CompetingStoreys(out);
      GateOnWallsSeen(evidence.walls, &out);
      stats_.milliseconds =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      return out;
    }
    // Before any room pair: what the proposals leave open (for inspection only).
    if (decision.status == MatchStatus::kNone && proposed.status == MatchStatus::kAmbiguous) {
      out.status = MatchStatus::kAmbiguous;
      out.hypotheses = static_cast<unsigned>(std::max<size_t>(1, 1 + proposed.competitors.size()));
      if (proposed.scored) {
        out.score = proposed.best.score;
        out.bim_T_map = proposed.best.pose.ToIsometry();
        out.storey = proposed.best.storey;
        for (const auto& c : proposed.competitors)
          out.alternatives.push_back({c.pose.ToIsometry(), c.score, 0, c.storey});
      }
    }
  }
  if (decision.status != MatchStatus::kNone || out.status == MatchStatus::kNone)
    out.status = decision.status;
  if (decision.best >= 0) {
    const Hypothesis& best = hypotheses[decision.best];
    last_best_ = best.pose;
    out.score = best.score;
    out.hypotheses = static_cast<unsigned>(1 + decision.competitors.size() + (doubt ? 1 : 0));
    out.bim_T_map = best.pose.ToIsometry();
    out.storey = best.storey;
    out.room_pairs = RoomPairs(best, s_rooms);
    out.surface_pairs = SurfacePairs(best, s_rooms);
    out.deviations = Deviations(best, s_rooms);
    out.doorway_pairs =
        doorways_.Pairs(evidence.doors, best.pose, best.storey, PairedRooms(best, s_rooms));
    for (int k : decision.competitors)
      out.alternatives.push_back({hypotheses[k].pose.ToIsometry(), hypotheses[k].score,
                                  hypotheses[k].rooms, hypotheses[k].storey});
    if (doubt)
      out.alternatives.push_back(
          {doubt->pose.ToIsometry(), doubt->score, doubt->rooms, doubt->storey});
    if (walls_view && walls_view->scored && decision.status != MatchStatus::kUnique) {
      out.alternatives.push_back(
          {walls_view->best.pose.ToIsometry(), walls_view->best.score, 0, walls_view->best.storey});
      ++out.hypotheses;
    }
  }
  if (scan_searched) FillScanSearch(&out);
  out.competing_storeys = CompetingStoreys(out);
  GateOnWallsSeen(evidence.walls, &out);
  stats_.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

void GraphMatcher::FillScanSearch(GraphMatch* out) const {
  if (!config_.scan_proposals) return;
  out->scan_set = scan_view_.certified ? static_cast<int>(scan_view_.set.size()) : -1;
  out->scan_margin = scan_view_.margin;
  out->scan_search = scan_view_.summary;
}

std::optional<Hypothesis> GraphMatcher::Doubt(const std::vector<RoomDescriptor>& s_rooms,
                                              const Hypothesis& best,
                                              const std::vector<Eigen::Vector2d>& s_points,
                                              const Evidence& evidence) {
  doubter_->stats_ = MatchStats{};  // its own bound on seeds, per call
  // Only a doubt within the margin of `best` counts: one whose affinity cannot reach that less
  // all the evidence it could gain is given up while it grows.
  const double evidence_bound =
      config_.surface_evidence_weight * surfaces_.Bound(evidence.loose) + DoorsBound(evidence);
  std::vector<Hypothesis> doubts =
      doubter_->Hypothesize(s_rooms, best.score - config_.ambiguity_margin - evidence_bound - 1e-9);
  doubter_->Score(doubts, evidence, s_rooms);
  std::optional<Hypothesis> strongest;
  for (auto& d : doubts) {
    if (d.members.empty() || d.score < best.score - config_.ambiguity_margin) continue;
    if (d.storey == best.storey && SameMotion(best.pose, d.pose, s_points, config_)) continue;
    // The doubter weighs the walked path and the sight lines only against its own best; a
    // doubt must have paid for the walls it goes through and the planes it could not have seen
    // before it competes with this best.
    if (d.crossings < 0) {
      Settle(
          d, [&](const Hypothesis& h) { return DoorsExplained(h, evidence, s_rooms); },
          [&](const Hypothesis& h) { return crossings_.Count(evidence.path, h.pose, h.storey); },
          [&](const Hypothesis& h) { return Hidden(h, evidence); }, config_);
      if (d.score < best.score - config_.ambiguity_margin) continue;
    }
    if (!strongest || d.score > strongest->score) strongest = std::move(d);
  }
  return strongest;
}

}  // namespace matching
}  // namespace is_graphs
