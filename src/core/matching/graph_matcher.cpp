#include "is_graphs/matching/graph_matcher.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/input_checks.h"
#include "is_graphs/matching/storeys_walked.h"
#include "is_graphs/sgraph/levels.h"

namespace is_graphs {
namespace matching {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

/// An S-room that moved this little since the last revision keeps its candidates.
bool Unchanged(const RoomDescriptor& a, const RoomDescriptor& b) {
  if (a.kind != b.kind || a.planes.size() != b.planes.size()) return false;
  if ((a.centre - b.centre).norm() > 0.05) return false;
  for (size_t i = 0; i < a.planes.size(); ++i) {
    const auto &p = a.planes[i], &q = b.planes[i];
    if (p.id != q.id || p.normal.dot(q.normal) < std::cos(0.5 * kDegToRad) ||
        std::abs(p.d - q.d) > 0.05)
      return false;
  }
  return true;
}

/// The S-rooms by distance from `anchor` (stable: ties keep their index order), the order in
/// which they are offered to a hypothesis grown from there.
std::vector<int> GrowthOrder(const std::vector<RoomDescriptor>& s_rooms,
                             const Eigen::Vector2d& anchor) {
  std::vector<std::pair<double, int>> by_distance;
  by_distance.reserve(s_rooms.size());
  for (size_t i = 0; i < s_rooms.size(); ++i)
    by_distance.emplace_back((s_rooms[i].centre - anchor).norm(), static_cast<int>(i));
  std::stable_sort(by_distance.begin(), by_distance.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<int> order;
  order.reserve(by_distance.size());
  for (const auto& [distance, i] : by_distance) order.push_back(i);
  return order;
}

Eigen::Vector2d MeanCentre(const std::vector<RoomDescriptor>& s_rooms) {
  Eigen::Vector2d anchor = Eigen::Vector2d::Zero();
  for (const auto& s : s_rooms) anchor += s.centre / static_cast<double>(s_rooms.size());
  return anchor;
}

}  // namespace

GraphMatcher::GraphMatcher(const MatcherConfig& config) : config_(config) {
  if (config.doubt_centre_tolerance > config.centre_tolerance) {
    MatcherConfig lenient = config;
    lenient.centre_tolerance = config.doubt_centre_tolerance;
    lenient.doubt_centre_tolerance = 0.0;  // the doubter does not doubt itself
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

Hypothesis GraphMatcher::Grow(const Pose2& start, const RoomCandidate* seed,
                              const std::vector<RoomDescriptor>& s_rooms,
                              const std::vector<std::vector<RoomCandidate>>& candidates,
                              const CandidateIndex& index, const std::vector<int>& order,
                              double affinity_floor, bool* abandoned) const {
  Hypothesis h;
  *abandoned = false;
  const auto strict = EvaluationTolerances::From(config_);
  // What the affinity could still reach: every S-room not yet turned away at its largest weight
  // (a pair's quality is at most 1).
  auto cap = [&](const RoomDescriptor& s) {
    return s.kind == RoomKind::kRoom ? std::max(1.0, config_.corridor_weight)
                                     : config_.corridor_weight;
  };
  double reachable = 0.0;
  for (const auto& s : s_rooms) reachable += cap(s);
  h.pose = start;
  std::vector<bool> a_taken(a_rooms_.size(), false);
  Eigen::Vector2d anchor = seed ? s_rooms[seed->s_room].centre : MeanCentre(s_rooms);
  RoomCorrespondence seed_corr;
  int storey = -1;  // the storey of the first pair; the others must be on it
  if (seed) {
    const auto& s = s_rooms[seed->s_room];
    const auto& a = a_rooms_[seed->a_room];
    seed_corr = ToCorrespondence(*seed, s, a);
    PairEvaluation eval = EvaluatePair(s, a, h.pose, seed->full_rank, strict);
    if (!eval.ok) return h;
    h.members.push_back({seed->s_room, seed->a_room, seed->full_rank, std::move(eval)});
    a_taken[seed->a_room] = seed->full_rank;
    storey = a.storey;
  }
  const double yaw_tol = config_.yaw_tolerance_deg * kDegToRad;
  const Eigen::Matrix2d seed_turn = Pose2{seed_corr.yaw, Eigen::Vector2d::Zero()}.R();
  std::vector<int> near;  // the candidates of an S-room that can be consistent with the seed
  for (int si : order) {
    if (seed && si == seed->s_room) continue;
    const RoomDescriptor& s = s_rooms[si];
    const auto tol = strict.Slackened(config_.lever_arm_slack * (s.centre - anchor).norm());
    const RoomCandidate* best = nullptr;
    PairEvaluation best_eval;
    // Without a seed (the last best motion grown again) every candidate may join.
    const Eigen::Vector2d ds = s.centre - seed_corr.s_centre;
    index.Near(si, seed_corr.a_centre + seed_turn * ds,
               seed
                   ? ConsistencyRadius(ds.norm(), config_.centre_tolerance, config_.lever_arm_slack)
                   : std::numeric_limits<double>::infinity(),
               &near);
    std::optional<Eigen::Matrix2d> turn;  // h.pose.R(), once for the candidates below
    for (int k : near) {
      const RoomCandidate& c = candidates[si][k];
      if (AngleDistance(c.pose.yaw, h.pose.yaw) > yaw_tol) continue;
      if (c.full_rank && a_taken[c.a_room]) continue;
      const RoomDescriptor& a = a_rooms_[c.a_room];
      if (storey >= 0 && a.storey != storey) continue;
      if (seed && !RoomPairsAgree(seed_corr, ToCorrespondence(c, s, a), config_)) continue;
      if (!turn) turn = h.pose.R();
      PairEvaluation eval = EvaluatePair(s, a, h.pose, *turn, c.full_rank, tol);
      if (eval.ok && (!best || eval.quality > best_eval.quality))
        best = &c, best_eval = std::move(eval);
    }
    if (!best) {
      reachable -= cap(s);
      if (reachable < affinity_floor) {  // it cannot matter: given up (its pairs so far kept)
        *abandoned = true;
        return h;
      }
      continue;
    }
    h.members.push_back({si, best->a_room, best->full_rank, std::move(best_eval)});
    if (best->full_rank) a_taken[best->a_room] = true;
    if (storey < 0) storey = a_rooms_[best->a_room].storey;
    const RigidFit fit = FitMembers(h.members, s_rooms, a_rooms_, config_);
    if (fit.translation_determined && fit.planes_determine_translation) h.pose = fit.pose;
  }
  // Final check of every pair under the motion fitted to all of them, without slack.
  for (int pass = 0; pass < 2 && !h.members.empty(); ++pass) {
    const RigidFit fit = FitMembers(h.members, s_rooms, a_rooms_, config_);
    if (fit.translation_determined && fit.planes_determine_translation) h.pose = fit.pose;
    std::vector<MemberPair> kept;
    for (auto& m : h.members) {
      m.evaluation =
          EvaluatePair(s_rooms[m.s_room], a_rooms_[m.a_room], h.pose, m.full_rank, strict);
      if (m.evaluation.ok) kept.push_back(std::move(m));
    }
    h.members = std::move(kept);
  }
  // A hypothesis must fix the motion: at least one full-rank pair.
  if (std::none_of(h.members.begin(), h.members.end(),
                   [](const MemberPair& m) { return m.full_rank; }))
    h.members.clear();
  h.storey = storey;
  h.affinity = h.score = GlobalAffinity(h.members, config_);
  h.rooms = static_cast<int>(h.members.size());
  return h;
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
  if (decision.status == MatchStatus::kUnique && config_.proposals &&
      config_.proposal_cross_check &&
      hypotheses[decision.best].rooms <= config_.proposal_cross_check_max_rooms &&
      !(last_checked_ &&
        SameMotion(*last_checked_, hypotheses[decision.best].pose, s_points, config_))) {
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
    ProposalDecision proposed = walls_view ? *walls_view : Propose(graph, evidence, hypotheses);
    if (walls_view) proposed.status = MatchStatus::kAmbiguous;  // the rooms say otherwise
    stats_.proposals = proposed.candidates;
    if (proposed.status == MatchStatus::kUnique) {
      FillFromProposal(proposed, hypotheses, s_rooms, evidence, &out);
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
  out.competing_storeys = CompetingStoreys(out);
  GateOnWallsSeen(evidence.walls, &out);
  stats_.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

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

std::vector<Hypothesis> GraphMatcher::Hypothesize(const std::vector<RoomDescriptor>& s_rooms,
                                                  double affinity_floor) {
  // 1. Local candidates, reused for S-rooms that did not change.
  std::map<int, CachedRoom> cache;
  std::vector<std::vector<RoomCandidate>> candidates(s_rooms.size());
  for (size_t i = 0; i < s_rooms.size(); ++i) {
    const auto it = cache_.find(s_rooms[i].id);
    if (it != cache_.end() && Unchanged(it->second.descriptor, s_rooms[i])) {
      candidates[i] = it->second.candidates;
      for (auto& c : candidates[i]) c.s_room = static_cast<int>(i);
      ++stats_.reused_rooms;
    } else {
      candidates[i] = GenerateRoomCandidates(s_rooms[i], static_cast<int>(i), a_rooms_, config_);
    }
    stats_.candidates += static_cast<int>(candidates[i].size());
    cache[s_rooms[i].id] = {s_rooms[i], candidates[i]};
  }
  cache_ = std::move(cache);
  if (!storeys_walked_.empty()) {  // the levels walked leave only some storeys (Match)
    for (auto& list : candidates) {
      list.erase(std::remove_if(list.begin(), list.end(),
                                [&](const RoomCandidate& c) {
                                  return !StoreyWalkable(a_rooms_[c.a_room].storey);
                                }),
                 list.end());
    }
  }

  // 2. Global candidates from seeds (best local candidates first), skipping seeds that an
  // earlier hypothesis already holds under the same motion.
  // A room paired through its walls alone (centre_off) seeds only where it is its S-room's
  // best fit on its storey (AC11's hall against the attic's): a weaker one may join a
  // hypothesis, and the seeds are what a match costs. Per storey: a twin floor's ordinary pair
  // must not keep this storey's hall from seeding.
  std::vector<const RoomCandidate*> seeds;
  std::map<int, double> best_ordinary;  // per storey, of one S-room
  for (const auto& list : candidates) {
    best_ordinary.clear();
    for (const auto& c : list)
      if (c.full_rank && !c.centre_off) {
        double& best = best_ordinary[a_rooms_[c.a_room].storey];
        best = std::max(best, c.quality);
      }
    for (const auto& c : list) {
      if (!c.full_rank) continue;
      const auto best = best_ordinary.find(a_rooms_[c.a_room].storey);
      if (!c.centre_off || best == best_ordinary.end() || c.quality > best->second)
        seeds.push_back(&c);
    }
  }
  std::stable_sort(seeds.begin(), seeds.end(), [](const RoomCandidate* x, const RoomCandidate* y) {
    return x->quality > y->quality;
  });
  std::vector<Hypothesis> hypotheses;
  const CandidateIndex index(candidates, a_rooms_);
  // The hypotheses holding each room pair (s_room * |A| + a_room), to find covered seeds: a
  // list per pair, linked through `held` (two allocations, not one per pair held).
  std::vector<int> held_head(s_rooms.size() * a_rooms_.size(), -1);
  std::vector<std::pair<int, int>> held;  // (hypothesis, next entry of its pair or -1)
  // A hypothesis given up (below affinity_floor) still covers the pairs it had, then has none.
  bool abandoned = false;
  auto add = [&](Hypothesis h) {
    for (const auto& m : h.members) {
      int& head = held_head[m.s_room * a_rooms_.size() + m.a_room];
      held.emplace_back(static_cast<int>(hypotheses.size()), head);
      head = static_cast<int>(held.size()) - 1;
    }
    if (abandoned) h.members.clear();
    hypotheses.push_back(std::move(h));
  };
  if (last_best_)
    add(Grow(*last_best_, nullptr, s_rooms, candidates, index,
             GrowthOrder(s_rooms, MeanCentre(s_rooms)), affinity_floor, &abandoned));
  std::vector<std::vector<int>> orders(s_rooms.size());  // from each S-room, made once
  for (const RoomCandidate* seed : seeds) {
    if (stats_.seeds >= config_.max_seeds) break;
    const std::vector<Eigen::Vector2d> at_seed{s_rooms[seed->s_room].centre};
    bool covered = false;
    for (int e = held_head[seed->s_room * a_rooms_.size() + seed->a_room]; e >= 0 && !covered;
         e = held[e].second) {
      const Hypothesis& k = hypotheses[held[e].first];
      covered = k.storey == a_rooms_[seed->a_room].storey &&
                SameMotion(k.pose, seed->pose, at_seed, config_);
    }
    if (covered) continue;
    ++stats_.seeds;
    std::vector<int>& order = orders[seed->s_room];
    if (order.empty()) order = GrowthOrder(s_rooms, s_rooms[seed->s_room].centre);
    add(Grow(seed->pose, seed, s_rooms, candidates, index, order, affinity_floor, &abandoned));
  }
  if (gate_ || only_storey_ >= 0)  // a pose hint's gate, SetStorey: the others left out
    hypotheses.erase(std::remove_if(hypotheses.begin(), hypotheses.end(),
                                    [&](const Hypothesis& h) { return !InGate(h.pose, h.storey); }),
                     hypotheses.end());
  return hypotheses;
}

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

std::map<int, int> GraphMatcher::PairedRooms(const Hypothesis& h,
                                             const std::vector<RoomDescriptor>& s_rooms) const {
  std::map<int, int> out;
  for (const auto& m : h.members) out[s_rooms[m.s_room].id] = a_rooms_[m.a_room].id;
  return out;
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
