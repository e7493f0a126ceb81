#pragma once

#include <Eigen/Core>
#include <unordered_map>
#include <utility>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/matching/rigid_fit.h"
#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace matching {

/// One walked step of the robot in M: from a keyframe's position to the next keyframe's.
using PathStep = std::pair<Eigen::Vector2d, Eigen::Vector2d>;

/// The walked steps of an S-Graph: each keyframe joined to its previous one, left out when
/// longer than `max_step` (a gap in the scans: the straight line is not where it walked).
std::vector<PathStep> WalkedPath(const sgraph::SGraph& graph, double max_step);

/// The walked path as evidence against a hypothesis: a legged robot goes through doorways,
/// never through walls. Under a motion bim_T_map, a step that crosses a wall-surface of the
/// storey farther than `door_margin` beyond every doorway's half-width contradicts it. Walls
/// not built yet, or openings the A-Graph has no doorway for, make the true motion cross too:
/// callers weigh the count, they do not veto on it. Surfaces are hashed into 1 m cells per
/// storey, so a count costs O(steps), not O(steps x surfaces).
class WallCrossings {
 public:
  WallCrossings() = default;
  WallCrossings(const agraph::AGraph& graph, double door_margin);

  /// The distinct walls (a wall's two surfaces count once) that `steps` cross under `pose` on
  /// `storey` (an A-Graph storey id).
  int Count(const std::vector<PathStep>& steps, const Pose2& pose, int storey) const;

 private:
  struct Surface {
    Eigen::Vector2d a, b;
    int wall;  // the A-Graph wall, or -1 - surface id for a surface of no wall
  };
  struct Door {
    Eigen::Vector2d position;
    double reach;  // half-width + margin
  };
  struct Storey {
    std::vector<Surface> surfaces;
    std::vector<Door> doors;
    std::unordered_map<long long, std::vector<int>> cells;  // 1 m cell -> surface indices
  };

  bool NearDoor(const Storey& storey, const Eigen::Vector2d& p) const;

  std::unordered_map<int, Storey> storeys_;
};

}  // namespace matching
}  // namespace is_graphs
