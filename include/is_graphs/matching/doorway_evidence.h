#pragma once

#include <Eigen/Core>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/matching/graph_match.h"
#include "is_graphs/matching/matcher_config.h"
#include "is_graphs/matching/rigid_fit.h"
#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace matching {

/// An S-Graph doorway the matcher can weigh: finite, between S-rooms that exist.
struct SDoorwayView {
  int id{0};
  Eigen::Vector2d at{Eigen::Vector2d::Zero()};  // in M
  double width{0.0};                            // 0: unknown
  std::vector<int> rooms;                       // S-room ids
};

/// The S-Graph's doorways that can be weighed; each one left out is named in `warnings`
/// (a non-finite position or width, a room that does not exist, doorways without any room).
std::vector<SDoorwayView> UsableDoorways(const sgraph::SGraph& graph,
                                         std::vector<std::string>* warnings);

/// The doorways the robot walked through as evidence for a hypothesis: under the true motion
/// each lies at a doorway of the BIM between the A-rooms its S-rooms pair with. An S-doorway
/// pairs with the nearest A-doorway of the storey within doorway_tolerance whose width agrees
/// within doorway_width_tolerance (when both are known) and whose rooms include the A-room the
/// hypothesis pairs with each of its S-rooms (an unpaired S-room does not constrain); each
/// A-doorway pairs at most once, nearest first. A pair scores exp(-d²/2σ²), σ = tolerance / 2.
/// Only positive: a doorway the BIM lacks (an opening cut on site) is no evidence either way;
/// the walls a path goes through are WallCrossings' to count.
class DoorwayEvidence {
 public:
  DoorwayEvidence() = default;
  DoorwayEvidence(const agraph::AGraph& graph, const MatcherConfig& config);

  /// (A-doorway id, S-doorway id, score) of the S-doorways lying at A-doorways under `pose`;
  /// `s_to_a_room` maps the hypothesis' S-room ids to A-room ids.
  std::vector<MatchPair> Pairs(const std::vector<SDoorwayView>& doorways, const Pose2& pose,
                               int storey, const std::map<int, int>& s_to_a_room) const;
  /// Σ of the pairs' scores.
  double Explained(const std::vector<SDoorwayView>& doorways, const Pose2& pose, int storey,
                   const std::map<int, int>& s_to_a_room) const;

 private:
  struct Door {
    int id;
    Eigen::Vector2d at;
    double width;
    std::vector<int> rooms;
  };
  double tolerance_{0.5};
  double width_tolerance_{0.35};
  struct Storey {
    std::vector<Door> doors;
    std::unordered_map<long long, std::vector<int>> cells;  // cell of side cell_ -> door indices
  };
  double cell_{1.0};  // m: at least doorway_tolerance, so a pair is in the 3 x 3 cells around
  std::unordered_map<int, Storey> storeys_;
};

}  // namespace matching
}  // namespace is_graphs
