// Steps 1-2 of GraphMatcher::Match: the local room-pair candidates (cached per S-room) and the
// global hypotheses grown from them, seed by seed.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "is_graphs/matching/graph_matcher.h"

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

}  // namespace matching
}  // namespace is_graphs
