#pragma once

#include <Eigen/Core>
#include <set>
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
/// never through walls. Under a motion bim_T_map, the path contradicts it where it goes through
/// a wall of the storey: into the wall by one face and out by the other, neither farther than
/// `door_margin` beyond a doorway's half-width, out within 1 m of where it went in. (Keyframes
/// walking along a wall wander across its near face with the pose noise and back out, or out
/// by the far face through the door, or, under a motion a little off, out by the far face metres
/// on: none is a crossing. A wall of one face is crossed wherever the path crosses it.) Walls
/// not built yet, or openings the A-Graph has no doorway for, make the true motion cross too:
/// callers weigh the count, they do not veto on it. Surfaces are hashed into 1 m cells per
/// storey, so a count costs O(steps), not O(steps x surfaces).
class WallCrossings {
 public:
  WallCrossings() = default;
  /// `sight_margin`: as door_margin, for sight lines (Blocks): a line of sight goes through the
  /// opening itself, where a walked path's keyframes wander with the pose noise.
  WallCrossings(const agraph::AGraph& graph, double door_margin, double sight_margin = 0.15);

  /// The distinct walls (a wall's two surfaces count once) that `steps` cross under `pose` on
  /// `storey` (an A-Graph storey id).
  int Count(const std::vector<PathStep>& steps, const Pose2& pose, int storey) const;

  /// Whether a sight line from `from` to `to` (in M) under `pose` goes through an interior wall
  /// of the storey (one whose faces all bound rooms) outside every doorway (its half-width +
  /// sight_margin), in by one face and
  /// out by the other. Exterior walls and walls of one face never block: they may hold windows
  /// the A-Graph does not have.
  bool Blocks(const Eigen::Vector2d& from, const Eigen::Vector2d& to, const Pose2& pose,
              int storey) const;

 private:
  struct Surface {
    Eigen::Vector2d a, b;
    Eigen::Vector2d normal;  // out of the wall's material
    int wall;                // the A-Graph wall, or -1 - surface id for a surface of no wall
    bool two_faced;          // its wall has another surface on the storey
    bool interior;           // two-faced and every face of its wall bounds a room
  };
  struct Door {
    Eigen::Vector2d position;
    double reach;        // half-width + door_margin
    double sight_reach;  // half-width + sight_margin
  };
  struct Storey {
    std::vector<Surface> surfaces;
    std::vector<Door> doors;
    std::unordered_map<long long, std::vector<int>> cells;  // 1 m cell -> surface indices
  };

  struct Entry {
    int surface;     // the face the path went in by
    bool near_door;  // ... at a doorway
    Eigen::Vector2d at;
  };

  bool NearDoor(const Storey& storey, const Eigen::Vector2d& p, bool sight) const;
  /// The walls `steps` go through (Count); with `sight`, interior walls only and the first
  /// one found ends the walk.
  std::set<int> Through(const std::vector<PathStep>& steps, const Pose2& pose, int storey,
                        bool sight) const;

  std::unordered_map<int, Storey> storeys_;
};

}  // namespace matching
}  // namespace is_graphs
