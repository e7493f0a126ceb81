#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace is_graphs {
namespace matching {

/// As msg/GraphMatch.msg: NONE (no hypothesis), AMBIGUOUS (competing hypotheses, or too little
/// evidence), UNIQUE (one hypothesis clearly best).
enum class MatchStatus { kNone = 0, kAmbiguous = 1, kUnique = 2 };

const char* ToString(MatchStatus status);

/// An A-Graph node (room or wall-surface id) and the S-Graph node (room or plane id) it matches.
struct MatchPair {
  int a_id{0};
  int s_id{0};
  double score{0.0};  // quality of the pair in [0, 1]
};

/// A wall-surface of a paired room that the S-Graph sees off the plan: the S-plane of the
/// paired S-room facing the way the A-surface does stands `offset` from it or is turned by
/// `angle`.
struct SurfaceDeviation {
  int a_id{0};         // A-Graph wall-surface
  int s_id{0};         // S-Graph plane
  double offset{0.0};  // m along the A-surface's normal (+: into the room it bounds), at the
                       // point of the plane nearest the A-room's centre
  double angle{0.0};   // rad, the S-plane's turn from the A-surface about z (+: anticlockwise)
  bool paired{false};  // within the pair tolerances (also in surface_pairs); else only here
};

/// A global hypothesis, as reported for the competitors of the best one.
struct HypothesisSummary {
  Eigen::Isometry3d bim_T_map{Eigen::Isometry3d::Identity()};
  double score{0.0};
  int rooms{0};    // matched S-rooms
  int storey{-1};  // its A-Graph storey id (a storey of the same plan is another hypothesis)
};

/// The matcher's answer for one S-Graph revision. For AMBIGUOUS the pairs and bim_T_map are
/// those of the best-scoring hypothesis, for inspection only (not to be acted on).
struct GraphMatch {
  MatchStatus status{MatchStatus::kNone};
  std::string a_graph_sha256;
  unsigned s_graph_revision{0};
  std::vector<MatchPair> room_pairs;  // A-room id, S-room id
  // A-wall-surface id, S-plane id; an S-plane along collinear A-surfaces (a face split by the
  // converter, a corridor wall split by doorways) is paired with each of them, same score.
  std::vector<MatchPair> surface_pairs;
  // A-doorway id, S-doorway id: the S-Graph's walked-through doorways at the BIM's
  // (DoorwayEvidence).
  std::vector<MatchPair> doorway_pairs;
  // Wall-surfaces of the paired rooms built off the plan (MatcherConfig deviation_*), one per
  // A-surface piece, by S-plane then A-surface id.
  std::vector<SurfaceDeviation> deviations;
  double score{0.0};       // global affinity of the best hypothesis
  unsigned hypotheses{0};  // hypotheses in the best score cluster (1 when UNIQUE)
  Eigen::Isometry3d bim_T_map{Eigen::Isometry3d::Identity()};  // rotation about z + translation
  // The best hypothesis's A-Graph storey id (-1 with no hypothesis). With the whole building
  // loaded this is the storey identified; alternatives on other storeys are other hypotheses.
  int storey{-1};
  std::vector<HypothesisSummary> alternatives;  // the other hypotheses of the best cluster
  std::vector<int> competing_storeys;           // CompetingStoreys(*this), set by the matcher
  std::vector<std::string> warnings;            // bad input found in either graph
  // What a pose hint did ("" without one; HintedMatching, pose_hint.h): "in force: ...",
  // "in force, agrees: ..." or "rejected: why".
  std::string hint;
  // The scan search on the newest keyframes' slices (MatcherConfig scan_proposals): the poses
  // the scans cannot tell apart (-1: no set: not run, or why in scan_search), the margin, and
  // what it found ("2 poses within 0.05 of the best 0.81 (storeys 0)", "too few points: ...").
  int scan_set{-1};
  double scan_margin{0.0};
  std::string scan_search;
};

/// The storeys of `match`'s competing hypotheses other than its own, sorted, distinct: not empty
/// when the match is in doubt about the storey (floors of one plan).
std::vector<int> CompetingStoreys(const GraphMatch& match);

}  // namespace matching
}  // namespace is_graphs
