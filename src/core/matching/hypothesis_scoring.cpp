#include "is_graphs/matching/hypothesis_scoring.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace is_graphs {
namespace matching {

double GlobalAffinity(const std::vector<MemberPair>& members, const MatcherConfig& config) {
  double score = 0.0;
  for (const auto& m : members)
    score += (m.full_rank ? 1.0 : config.corridor_weight) * m.evaluation.quality;
  return score;
}

void Settle(Hypothesis& h, const std::function<double(const Hypothesis&)>& lazy,
            const std::function<int(const Hypothesis&)>& crossings,
            const std::function<double(const Hypothesis&)>& hidden, const MatcherConfig& config) {
  if (h.crossings >= 0) return;
  const double exact = h.pending > 0.0 ? lazy(h) : 0.0;
  h.evidence += exact;
  h.score += exact - h.pending;
  h.pending = 0.0;
  h.crossings = config.wall_crossing_penalty > 0.0 ? crossings(h) : 0;
  h.score -= config.wall_crossing_penalty * h.crossings;
  h.hidden = config.sight_penalty > 0.0 ? hidden(h) : 0.0;
  h.score -= h.hidden;
}

void ScoreHypotheses(std::vector<Hypothesis>& hypotheses,
                     const std::function<double(const Hypothesis&)>& evidence,
                     const std::function<double(const Hypothesis&)>& lazy, double lazy_bound,
                     const std::function<int(const Hypothesis&)>& crossings,
                     const std::function<double(const Hypothesis&)>& hidden,
                     const MatcherConfig& config) {
  std::vector<int> order;
  for (size_t k = 0; k < hypotheses.size(); ++k) {
    Hypothesis& h = hypotheses[k];
    h.crossings = -1;
    h.hidden = 0.0;
    h.evidence = h.members.empty() ? 0.0 : evidence(h);
    h.pending = h.members.empty() ? 0.0 : std::max(0.0, lazy_bound);
    h.score = h.affinity + h.evidence + h.pending;
    if (!h.members.empty()) order.push_back(static_cast<int>(k));
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](int x, int y) { return hypotheses[x].score > hypotheses[y].score; });
  double best = -std::numeric_limits<double>::infinity();
  for (int k : order) {
    Hypothesis& h = hypotheses[k];
    if (h.score < best - config.ambiguity_margin) break;  // sorted bounds: no later one matters
    if (h.pending > 0.0) {  // the lazy evidence first: it may put h out of reach by itself
      const double exact = lazy(h);
      h.evidence += exact;
      h.score += exact - h.pending;
      h.pending = 0.0;
      if (h.score < best - config.ambiguity_margin) continue;
    }
    Settle(h, lazy, crossings, hidden, config);
    best = std::max(best, h.score);
  }
}

RigidFit FitMembers(const std::vector<MemberPair>& members,
                    const std::vector<RoomDescriptor>& s_rooms,
                    const std::vector<RoomDescriptor>& a_rooms, const MatcherConfig& config) {
  std::vector<PlaneCorrespondence> planes;
  std::vector<PointCorrespondence> points;
  size_t n = 0;
  for (const auto& m : members) n += m.evaluation.surfaces.size();
  planes.reserve(n);
  points.reserve(members.size());
  for (const auto& m : members) {
    const RoomDescriptor& s = s_rooms[m.s_room];
    const RoomDescriptor& a = a_rooms[m.a_room];
    for (const auto& [i, j] : m.evaluation.surfaces)
      planes.push_back(
          {s.planes[i].normal, s.planes[i].d, a.planes[j].normal, a.planes[j].d, a.centre});
    // A pair whose S-centre a plane standing in the room moved: its planes alone.
    if (m.full_rank && !m.evaluation.centre_off)
      points.push_back({s.centre, a.centre, config.centre_tolerance});
  }
  return FitYawTranslation(planes, points);
}

bool SameMotion(const Pose2& a, const Pose2& b, const std::vector<Eigen::Vector2d>& points,
                const MatcherConfig& config) {
  if (AngleDistance(a.yaw, b.yaw) > config.cluster_yaw_deg * M_PI / 180.0) return false;
  if (points.empty()) return (a.t - b.t).norm() <= config.cluster_translation;
  const Eigen::Matrix2d ra = a.R(), rb = b.R();  // once, not per point
  return std::all_of(points.begin(), points.end(), [&](const Eigen::Vector2d& p) {
    return ((ra * p + a.t) - (rb * p + b.t)).norm() <= config.cluster_translation;
  });
}

Decision Decide(std::vector<Hypothesis>& hypotheses, const std::vector<Eigen::Vector2d>& s_points,
                int s_room_count, const MatcherConfig& config) {
  Decision decision;
  hypotheses.erase(std::remove_if(hypotheses.begin(), hypotheses.end(),
                                  [](const Hypothesis& h) { return h.members.empty(); }),
                   hypotheses.end());
  if (hypotheses.empty()) return decision;
  // Deterministic order: score, then the pairs themselves.
  auto key = [](const Hypothesis& h) {
    std::vector<std::pair<int, int>> pairs;
    for (const auto& m : h.members) pairs.emplace_back(m.s_room, m.a_room);
    std::sort(pairs.begin(), pairs.end());
    return pairs;
  };
  std::stable_sort(hypotheses.begin(), hypotheses.end(),
                   [&](const Hypothesis& x, const Hypothesis& y) {
                     if (x.score != y.score) return x.score > y.score;
                     return key(x) < key(y);
                   });
  // Cluster by motion: a hypothesis implying the motion of a better one is that one. Only the
  // clusters within the margin of the best matter (they come first: sorted by score).
  std::vector<int> clusters;
  for (size_t i = 0; i < hypotheses.size(); ++i) {
    if (hypotheses[i].score < hypotheses.front().score - config.ambiguity_margin) break;
    const bool known = std::any_of(clusters.begin(), clusters.end(), [&](int c) {
      return hypotheses[c].storey == hypotheses[i].storey &&
             SameMotion(hypotheses[c].pose, hypotheses[i].pose, s_points, config);
    });
    if (!known) clusters.push_back(static_cast<int>(i));
  }
  decision.best = clusters.front();
  const Hypothesis& best = hypotheses[decision.best];
  for (size_t k = 1; k < clusters.size(); ++k)
    if (hypotheses[clusters[k]].score >= best.score - config.ambiguity_margin)
      decision.competitors.push_back(clusters[k]);
  const bool enough = best.rooms >= config.min_matched_rooms &&
                      best.rooms >= config.min_matched_fraction * s_room_count - 1e-9;
  decision.status =
      decision.competitors.empty() && enough ? MatchStatus::kUnique : MatchStatus::kAmbiguous;
  return decision;
}

}  // namespace matching
}  // namespace is_graphs
