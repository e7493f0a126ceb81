#pragma once

#include <algorithm>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/matching/candidate_graph.h"
#include "is_graphs/matching/candidate_index.h"
#include "is_graphs/matching/corner_proposals.h"
#include "is_graphs/matching/doorway_evidence.h"
#include "is_graphs/matching/graph_match.h"
#include "is_graphs/matching/hypothesis_scoring.h"
#include "is_graphs/matching/matcher_config.h"
#include "is_graphs/matching/pose_hint.h"
#include "is_graphs/matching/room_descriptor.h"
#include "is_graphs/matching/scan_search.h"
#include "is_graphs/matching/sight_evidence.h"
#include "is_graphs/matching/surface_evidence.h"
#include "is_graphs/matching/wall_crossings.h"
#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace matching {

/// What the last Match did (for logs and the benchmark).
struct MatchStats {
  int s_rooms{0};       // usable S-rooms
  int candidates{0};    // local room-pair candidates
  int reused_rooms{0};  // S-rooms whose candidates came from the previous revision
  int seeds{0};         // global candidates grown
  int hypotheses{0};    // distinct global candidates scored
  int proposals{0};     // motions proposed by corners (step 6), 0 when not run
  double milliseconds{0.0};
};

/// The hierarchical A-Graph <-> S-Graph matcher (iS-Graphs' graph matching, made deterministic):
///  1. top-down candidates: per S-room, the A-rooms whose surfaces it can be (categorical,
///     structural and point-normal checks), with the surface pairs and the motion they imply;
///  2. bottom-up global candidates: from each full-rank room pair as a seed, the other S-rooms
///     join in order of distance when a room pair of theirs is consistent with the seed pair
///     (pairwise, CLIPPER-style) and with the motion refitted so far; finally re-checked under
///     the motion fitted to everything, and scored by global affinity;
///  3. score: the affinity, plus the loose wall planes (of no S-room, or of S-rooms no
///     hypothesis pairs: seen through doorways, a room built off the plan) that lie on BIM
///     wall-surfaces under its motion, plus the doorways the robot walked through that lie at
///     BIM doorways between the paired rooms (DoorwayEvidence), less what contradicts it: BIM
///     walls the robot's walked path (its keyframes) crosses away from every doorway, and
///     loose planes it could only have seen through an interior BIM wall (HiddenWalls);
///  4. decision: hypotheses implying the same motion merged, the best score cluster
///     (ambiguity_margin) must hold exactly one for UNIQUE (see Decide);
///  5. doubt: a UNIQUE answer is re-checked by a second matcher whose room-centre gate is
///     doubt_centre_tolerance: where clutter moved the true room's centre out of the strict
///     gate, the truth is missing from the hypotheses and a lone wrong one would stand; a
///     hypothesis of another motion it finds within the margin makes the answer AMBIGUOUS
///     (scored on the same loose planes: its own pairs would leave others loose).
///  6. proposals (when 1-5 give no UNIQUE answer, e.g. before any room is closed): motions
///     mapping corners of the seen wall planes onto the BIM's corners, with the hypotheses'
///     motions, scored on every wall plane seen, the walked path and the sight lines (Propose);
///     one clearly best gives UNIQUE with its surface pairs (and its room pairs where a
///     hypothesis of the same motion has them). A UNIQUE answer of steps 1-5 is checked the
///     same way (proposal_cross_check): if the wall planes clearly prefer another motion, the
///     answer is AMBIGUOUS.
/// Incremental: an S-room unchanged since the last call keeps its candidates, and the last best
/// motion is grown first. Not thread-safe; one matcher per thread.
class GraphMatcher {
 public:
  explicit GraphMatcher(const MatcherConfig& config = {});

  /// Sets or replaces the A-Graph (forgetting the incremental state); returns its warnings.
  std::vector<std::string> SetAGraph(const agraph::AGraph& graph);
  bool HasAGraph() const { return has_agraph_; }

  /// Matches one S-Graph revision. Bad input is reported in GraphMatch::warnings and left out;
  /// nothing usable gives NONE. An S-Graph over several levels (stairs walked) is matched on
  /// the level of its newest keyframe: a storey's plan against one storey's; the history is
  /// forgotten when the level changes.
  GraphMatch Match(const sgraph::SGraph& graph);
  /// Forgets the S-Graph matched so far (it restarted): no reuse, no previous best motion.
  void ForgetHistory() {
    level_storeys_.clear();
    cache_.clear();
    last_best_.reset();
    last_checked_.reset();
    scan_view_ = ScanView();
    if (doubter_) doubter_->ForgetHistory();
  }

  /// Leaves out every hypothesis (rooms', doubter's, proposals') outside `gate` until called
  /// with null; `gate` must outlive that (HintedMatching, pose_hint.h).
  void SetGate(const HintGate* gate) {
    gate_ = gate;
    if (doubter_) doubter_->SetGate(gate);
  }
  /// Leaves out every hypothesis on another storey than `storey` (an A-Graph storey id; -1:
  /// any), as a gate does; forgets the history.
  void SetStorey(int storey) {
    only_storey_ = storey;
    ForgetHistory();
    if (doubter_) doubter_->SetStorey(storey);
  }
  int OnlyStorey() const { return only_storey_; }

  const MatchStats& LastStats() const { return stats_; }
  const MatcherConfig& config() const { return config_; }
  const std::vector<RoomDescriptor>& ARooms() const { return a_rooms_; }

 private:
  struct CachedRoom {
    RoomDescriptor descriptor;
    std::vector<RoomCandidate> candidates;
  };

  /// Steps 1-2 of Match: candidates (cached), hypotheses grown from seeds. A hypothesis whose
  /// affinity cannot reach `affinity_floor` is given up while it grows (left without members).
  std::vector<Hypothesis> Hypothesize(
      const std::vector<RoomDescriptor>& s_rooms,
      double affinity_floor = -std::numeric_limits<double>::infinity());
  /// The wall planes weighed as evidence (SurfaceEvidence): those of no S-room and of S-rooms
  /// none of `hypotheses` pairs.
  std::vector<WallSegment> LooseWalls(const sgraph::SGraph& graph,
                                      const std::vector<WallSegment>& walls,
                                      const std::vector<RoomDescriptor>& s_rooms,
                                      const std::vector<Hypothesis>& hypotheses) const;
  /// What one S-Graph shows beyond its rooms, the same for every hypothesis and the doubter.
  struct Evidence {
    std::vector<WallSegment> walls;   // every wall plane seen (WallSegments)
    std::vector<PathStep> path;       // the walked path
    std::vector<WallSegment> loose;   // the loose wall planes (LooseWalls)
    std::vector<SeenWall> seen;       // ... with the keyframes that observed them
    std::vector<SDoorwayView> doors;  // the doorways walked through
    // Whether the loose planes outside the building count against a hypothesis (Match weighs
    // them only while the best puts none outside).
    bool outside{true};
  };
  /// Step 3: scores `hypotheses` on their pairs and the `evidence`.
  void Score(std::vector<Hypothesis>& hypotheses, const Evidence& evidence,
             const std::vector<RoomDescriptor>& s_rooms) const;
  /// doorway_evidence_weight x the doorways walked through that lie at BIM doorways under `h`,
  /// and its bound (each pair scores at most 1).
  double DoorsExplained(const Hypothesis& h, const Evidence& evidence,
                        const std::vector<RoomDescriptor>& s_rooms) const;
  double DoorsBound(const Evidence& evidence) const;
  /// sight_penalty x the loose planes `h` could not have seen (HiddenWalls).
  double Hidden(const Hypothesis& h, const Evidence& evidence) const;
  /// S-room id -> A-room id of the pairs of `h`.
  std::map<int, int> PairedRooms(const Hypothesis& h,
                                 const std::vector<RoomDescriptor>& s_rooms) const;
  /// A hypothesis of another motion than `best` that the doubter finds within the margin.
  std::optional<Hypothesis> Doubt(const std::vector<RoomDescriptor>& s_rooms,
                                  const Hypothesis& best,
                                  const std::vector<Eigen::Vector2d>& s_points,
                                  const Evidence& evidence);

  /// Step 6: the proposals' decision. `best` and `competitors` carry pose, storey and score.
  struct ProposalDecision {
    MatchStatus status{MatchStatus::kNone};
    Hypothesis best;
    std::vector<Hypothesis> competitors;
    std::vector<WallSegment> walls;  // the wall planes it was decided on
    // Other motions explaining proposal_margin more of the walls than `best` (that lost on
    // crossings or sight lines).
    std::vector<Hypothesis> more_walls;
    int candidates{0};
    bool scored{false};  // best and competitors were scored (else too many to decide)
  };
  /// With `hypotheses_if_too_many`, where the corners fit too many places, the hypotheses'
  /// motions alone are weighed (never UNIQUE then): the check of a UNIQUE room answer.
  ProposalDecision Propose(const sgraph::SGraph& graph, const Evidence& evidence,
                           const std::vector<Hypothesis>& hypotheses,
                           bool hypotheses_if_too_many = false) const;
  /// Whether the proposals' decision puts `best` (the rooms' UNIQUE answer) outside its best
  /// cluster: the wall planes seen clearly prefer another motion (proposal_cross_check).
  bool WallsPreferAnother(const ProposalDecision& proposed, const Hypothesis& best) const;
  /// Fills `out` (UNIQUE) from a proposal: its surface pairs, and the room pairs of a
  /// hypothesis of the same motion.
  void FillFromProposal(const ProposalDecision& proposed, const std::vector<Hypothesis>& hypotheses,
                        const std::vector<RoomDescriptor>& s_rooms, const Evidence& evidence,
                        GraphMatch* out);
  /// The room pairs of `h` (by S-room id) and its surface pairs (an S-plane with every piece of
  /// its best-scoring A-feature).
  std::vector<MatchPair> RoomPairs(const Hypothesis& h,
                                   const std::vector<RoomDescriptor>& s_rooms) const;
  std::vector<MatchPair> SurfacePairs(const Hypothesis& h,
                                      const std::vector<RoomDescriptor>& s_rooms) const;
  /// The wall-surfaces of the rooms `h` pairs that their S-planes show off the plan.
  std::vector<SurfaceDeviation> Deviations(const Hypothesis& h,
                                           const std::vector<RoomDescriptor>& s_rooms) const;
  /// `pose` refitted to the planes of `walls` and the A-surfaces they lie along under it.
  Pose2 Refine(const std::vector<WallSegment>& walls, const Pose2& pose, int storey) const;

  // The scan search (graph_matcher_scans.cpp): the poses the newest keyframes' slices cannot
  // tell apart, on every storey a proposal may be on.
  struct ScanPoseOn {
    Pose2 pose;
    int storey{-1};
    double score{0.0};
  };
  struct ScanView {
    bool certified{false};        // `set` holds every pose within `margin` of the best
    std::vector<ScanPoseOn> set;  // best first
    double best{0.0}, margin{0.0};
    std::string summary;      // GraphMatch::scan_search
    std::vector<double> key;  // what it was made of (SearchScans)
    double milliseconds{0.0};
  };
  const ScanView& SearchScans(const sgraph::SGraph& graph);
  /// Whether `h` is one of the scan set's poses (always true without a certified set).
  bool InScanSet(const Hypothesis& h, const std::vector<Eigen::Vector2d>& points) const;
  void FillScanSearch(GraphMatch* out) const;

  Hypothesis Grow(const Pose2& start, const RoomCandidate* seed,
                  const std::vector<RoomDescriptor>& s_rooms,
                  const std::vector<std::vector<RoomCandidate>>& candidates,
                  const CandidateIndex& index, const std::vector<int>& order, double affinity_floor,
                  bool* abandoned) const;

  GraphMatch MatchLevel(const sgraph::SGraph& graph);
  /// A UNIQUE `out` whose motion fits too little of the walls seen becomes AMBIGUOUS
  /// (unique_min_wall_share).
  void GateOnWallsSeen(const std::vector<WallSegment>& walls, GraphMatch* out) const;

  MatcherConfig config_;
  bool has_agraph_{false};
  std::string a_sha256_;
  std::vector<RoomDescriptor> a_rooms_;
  WallCrossings crossings_;
  SurfaceEvidence surfaces_;
  DoorwayEvidence doorways_;
  std::vector<Corner> a_corners_;
  ScanSearch scan_;     // built with the A-Graph when scan_proposals
  ScanView scan_view_;  // of the last SearchScans, reused while its keyframes are the same
  std::map<int, CachedRoom> cache_;  // by S-room id
  std::optional<Pose2> last_best_;
  std::optional<Pose2> last_checked_;        // the last UNIQUE motion the walls agreed with
  int level_{0};                             // of the S-Graph level matched last
  int a_storeys_{0};                         // storeys in the A-Graph
  std::map<int, double> storey_elevations_;  // A-Graph storey id -> elevation
  // The storeys the levels walked leave possible for the current one (StoreysFittingLevels);
  // empty: any. Candidates and proposals on others are not made.
  std::vector<int> storeys_walked_;
  // The storey of each S-Graph level its latest UNIQUE match named (StoreysFromKnownLevels);
  // kept across level changes, forgotten with the S-Graph (ForgetHistory) or the A-Graph.
  std::map<int, int> level_storeys_;
  GraphMatch Remember(int level, GraphMatch match);
  bool StoreyWalkable(int storey) const {
    return storeys_walked_.empty() || std::find(storeys_walked_.begin(), storeys_walked_.end(),
                                                storey) != storeys_walked_.end();
  }
  bool InGate(const Pose2& pose, int storey) const {
    return (only_storey_ < 0 || storey == only_storey_) && (!gate_ || gate_->Inside(pose, storey));
  }
  const HintGate* gate_{nullptr};  // a pose hint's gate (SetGate), null: none
  int only_storey_{-1};            // SetStorey
  MatchStats stats_;
  /// The same matcher with doubt_centre_tolerance (null: no doubt). Owning it makes a
  /// GraphMatcher move-only: one per thread, as said above.
  std::unique_ptr<GraphMatcher> doubter_;
};

}  // namespace matching
}  // namespace is_graphs
