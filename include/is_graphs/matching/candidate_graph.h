#pragma once

#include <Eigen/Core>
#include <cmath>
#include <utility>
#include <vector>

#include "is_graphs/matching/matcher_config.h"
#include "is_graphs/matching/pairwise_consistency.h"
#include "is_graphs/matching/rigid_fit.h"
#include "is_graphs/matching/room_descriptor.h"

namespace is_graphs {
namespace matching {

// The match-candidates graph, built top-down: room pairs (an S-room and an A-room that pass the
// categorical, structural and geometric checks) and, under each, the surface pairs that make it.

struct EvaluationTolerances {
  double offset{0.3};
  double centre{0.6};
  double angle_rad{0.14};
  double min_cos{std::cos(0.14)};  // cos(angle_rad): From sets both (once, not per pair)
  double min_plane_fraction{0.5};
  double quality_sigma{0.12};
  bool centre_off{true};  // MatcherConfig::pair_through_walls

  static EvaluationTolerances From(const MatcherConfig& config, double slack = 0.0);
  /// These with `slack` more on offsets and centres (From(config, slack) of a From(config)).
  EvaluationTolerances Slackened(double slack) const {
    EvaluationTolerances t = *this;
    t.offset += slack;
    t.centre += slack;
    return t;
  }
};

/// A room pair under a given motion: which S-planes found which A-surfaces, how well.
struct PairEvaluation {
  bool ok{false};
  double quality{0.0};  // (matched share of S-planes) (½ + ½ A-coverage) mean exp(-r²/2σ²)
  double rms{0.0};
  std::vector<std::pair<int, int>> surfaces;  // (S-plane index, A-plane index) in the descriptors
  std::vector<double> residuals;              // per surface pair [m]
  // A full-rank pair whose S-centre missed the A-centre: all S-planes but one paired, two of
  // them facing each other, and the one left standing inside the A-room (a stair's side, a
  // cabinet or a partition not in the plan taken for a bound of the room). Its S-centre is then
  // no point correspondence.
  bool centre_off{false};
};

/// Evaluates S-room `s` against A-room `a` under `pose` (bim_T_map). With `full_rank` the moved
/// S-centre must lie within the centre tolerance of the A-centre (or, `centre_off`, inside the
/// A-room with one S-plane inside it unpaired and at least three paired, two facing each
/// other), otherwise (a corridor, or a room whose planes are all parallel) within the tolerance
/// of the A-room's footprint.
PairEvaluation EvaluatePair(const RoomDescriptor& s, const RoomDescriptor& a, const Pose2& pose,
                            bool full_rank, const EvaluationTolerances& tolerances);
/// The same with `rotation` = pose.R() already at hand (a fit's, turned once).
PairEvaluation EvaluatePair(const RoomDescriptor& s, const RoomDescriptor& a, const Pose2& pose,
                            const Eigen::Matrix2d& rotation, bool full_rank,
                            const EvaluationTolerances& tolerances);

/// A local candidate: an S-room, an A-room and the motion their surfaces alone imply.
struct RoomCandidate {
  int s_room{0};  // indices into the descriptor vectors
  int a_room{0};
  Pose2 pose;
  bool full_rank{false};  // the surfaces fix the motion; else free along `axis` (in B)
  Eigen::Vector2d axis{Eigen::Vector2d::UnitX()};
  double quality{0.0};
  bool centre_off{false};  // paired through its planes only (PairEvaluation::centre_off)
  Eigen::Vector2d at{Eigen::Vector2d::Zero()};  // where `pose` puts the S-centre (in B)
};

/// The local candidates of one S-room against every A-room: yaws from pairing an anchor S-plane
/// with each A-surface at the same distance from the centre (no blind permutations), surfaces
/// paired under each yaw and pruned by pairwise point-normal consistency, the motion fitted,
/// the pair evaluated. Where that fails for a room of four or more paired planes, each pair is
/// left out in turn and the motion fitted to the others (no centre prior): one plane that is
/// not the room's bound must not hide the room. At most one candidate per A-room and yaw.
std::vector<RoomCandidate> GenerateRoomCandidates(const RoomDescriptor& s, int s_index,
                                                  const std::vector<RoomDescriptor>& a_rooms,
                                                  const MatcherConfig& config);

/// The correspondence of a candidate for RoomPairConsistency (a `centre_off` one pairs its
/// S-centre with where its own motion puts it, not with the A-centre).
RoomCorrespondence ToCorrespondence(const RoomCandidate& c, const RoomDescriptor& s,
                                    const RoomDescriptor& a);

}  // namespace matching
}  // namespace is_graphs
