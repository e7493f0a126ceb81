#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "is_graphs/matching/candidate_graph.h"
#include "is_graphs/matching/graph_match.h"
#include "is_graphs/matching/matcher_config.h"
#include "is_graphs/matching/rigid_fit.h"
#include "is_graphs/matching/room_descriptor.h"

namespace is_graphs {
namespace matching {

/// One room pair of a global hypothesis, evaluated under the hypothesis' motion.
struct MemberPair {
  int s_room{0};  // descriptor indices
  int a_room{0};
  bool full_rank{false};
  PairEvaluation evaluation;
};

/// A global candidate: room pairs combined bottom-up under one motion, and its score: the
/// global affinity of its pairs less what contradicts it.
struct Hypothesis {
  Pose2 pose;      // bim_T_map
  int storey{-1};  // the A-Graph storey of its pairs (a hypothesis keeps to one)
  std::vector<MemberPair> members;
  double affinity{0.0};  // GlobalAffinity of the members
  double evidence{0.0};  // weighted SurfaceEvidence of the loose wall planes + DoorwayEvidence
                         // - outside
  double outside{0.0};   // outside_penalty x SurfaceEvidence::Outside of the loose planes
  int crossings{-1};     // walls the walked path crosses under `pose`; -1: not evaluated
  double hidden{0.0};    // sight_penalty x HiddenWalls of the loose planes (with crossings)
  // The bound on the lazy evidence still in `score` in its place (with crossings = -1: not
  // evaluated; ScoreHypotheses).
  double pending{0.0};
  double score{0.0};
  int rooms{0};  // matched S-rooms
};

/// Σ over the pairs of weight × quality (weight 1 for a room, corridor_weight for a pair that
/// fixes the motion only across an axis).
double GlobalAffinity(const std::vector<MemberPair>& members, const MatcherConfig& config);

/// Scores every hypothesis: affinity + evidence(h) + lazy(h) - wall_crossing_penalty x
/// crossings(h) - hidden(h): evidence(h) and lazy(h) what the S-Graph shows beyond the pairs that
/// fits h (wall planes on the BIM's surfaces, doorways at its doorways, already weighted),
/// crossings(h) the walls the walked path crosses under its motion, hidden(h) the weighted wall
/// planes it could not have seen under it. lazy(h) (at most lazy_bound), crossings(h) and
/// hidden(h) are evaluated best first and only while they can still change the decision: a
/// hypothesis whose score with lazy_bound in place of lazy(h) is more than ambiguity_margin
/// below the best score so far can neither win nor compete, and keeps crossings = -1 and that
/// optimistic score (pending = lazy_bound; Settle finishes it); one within reach gets lazy(h)
/// first, and its crossings and hidden planes only if it is still within reach.
/// (Penalising S-rooms a hypothesis pairs with nothing was tried and left out: it widened the
/// gaps between partial hypotheses of a mirror image until one became UNIQUE.)
void ScoreHypotheses(std::vector<Hypothesis>& hypotheses,
                     const std::function<double(const Hypothesis&)>& evidence,
                     const std::function<double(const Hypothesis&)>& lazy, double lazy_bound,
                     const std::function<int(const Hypothesis&)>& crossings,
                     const std::function<double(const Hypothesis&)>& hidden,
                     const MatcherConfig& config);

/// Evaluates what ScoreHypotheses left pending on `h` (crossings = -1): its lazy evidence in
/// place of the bound, its crossings and hidden planes.
void Settle(Hypothesis& h, const std::function<double(const Hypothesis&)>& lazy,
            const std::function<int(const Hypothesis&)>& crossings,
            const std::function<double(const Hypothesis&)>& hidden, const MatcherConfig& config);

/// The motion fitted to all surface pairs of the members and the centres of the full-rank ones.
RigidFit FitMembers(const std::vector<MemberPair>& members,
                    const std::vector<RoomDescriptor>& s_rooms,
                    const std::vector<RoomDescriptor>& a_rooms, const MatcherConfig& config);

/// True when the two motions agree within the cluster tolerances at every one of `points` (the
/// S-Graph's room centres, in M): the same hypothesis up to noise.
bool SameMotion(const Pose2& a, const Pose2& b, const std::vector<Eigen::Vector2d>& points,
                const MatcherConfig& config);

/// The decision over a set of hypotheses: sorted by score, merged where they imply the same
/// motion on the same storey (storeys with one plan imply one planar motion: they compete), the
/// best cluster = those within ambiguity_margin of the best. UNIQUE when it holds one hypothesis
/// that pairs at least min_matched_rooms and min_matched_fraction of the `s_room_count` rooms; NONE
/// when there is no hypothesis; else AMBIGUOUS.
struct Decision {
  MatchStatus status{MatchStatus::kNone};
  int best{-1};                  // index into the (sorted) hypotheses
  std::vector<int> competitors;  // other members of the best cluster
};

Decision Decide(std::vector<Hypothesis>& hypotheses, const std::vector<Eigen::Vector2d>& s_points,
                int s_room_count, const MatcherConfig& config);

}  // namespace matching
}  // namespace is_graphs
