#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace sgraph {

/// Storeys walked (issue 22): a level is a height in M the robot walked on. A stair climb ends
/// on a new level once the robot has risen or fallen `min_rise` from every level known and
/// settled there (two keyframes within `settle`); keyframes on the flight keep the level they
/// left. Coming back to a known level's height puts it on that level again. A new level the
/// robot leaves after walking less than `landing_length` on it, climbing on the same way to
/// settle again out of its tolerance (a landing of a multi-flight stair, AC11's two thirds up),
/// moves to that height: the level is the floor the climb ends on, not its landing.
struct LevelConfig {
  double tolerance{0.5};       // m: a keyframe this close to a level's height is on it
  double min_rise{1.5};        // m: a new level lies this far from all others, at least
  double settle{0.15};         // m: between two keyframes standing on a new level
  double landing_length{4.0};  // m walked on a new level left, the climb going on: a landing
  std::string Validate() const;
};

class LevelTracker {
 public:
  explicit LevelTracker(const LevelConfig& config = {}) : config_(config) {}

  /// The level of the next keyframe, at `position` (its base_link in M).
  int Add(const Eigen::Vector3d& position);
  /// As above, standing still in x-y.
  int Add(double z) { return Add(Eigen::Vector3d(last_xy_.x(), last_xy_.y(), z)); }
  void Reset() { heights_.clear(), current_ = from_ = -1, on_current_ = 0.0, has_last_ = false; }
  /// The height of level `level`: its first keyframe's (the last one settled on, for a level
  /// moved off a landing).
  double Height(int level) const { return heights_[level]; }
  int size() const { return static_cast<int>(heights_.size()); }

 private:
  LevelConfig config_;
  std::vector<double> heights_;
  int current_{-1};
  int from_{-1};            // the level the climb to the current (new) level came from
  double on_current_{0.0};  // m walked on the current level since the climb made it
  double last_z_{0.0};
  Eigen::Vector2d last_xy_{Eigen::Vector2d::Zero()};
  bool has_last_{false};
};

/// The level of the newest keyframe (0 for an empty graph).
int CurrentLevel(const SGraph& graph);
/// How far the newest keyframe lies above (+) or below (-) the first keyframe of its level, in
/// M (0 for an empty graph): beyond the level tolerance the robot is on a stair, still counted
/// on the level it left until it settles.
double HeightOffLevel(const SGraph& graph);
/// Whether the robot is on a stair: its newest keyframe more than `tolerance` off its level
/// (HeightOffLevel) while still rising or falling (one of the two keyframes before it more than
/// `settle` away in height). Settled off its level (a long landing the level tracker took for a
/// level, a plateau) it is not: the level's own map is matched there.
bool OnStair(const SGraph& graph, double tolerance, double settle = 0.15);
/// Whether keyframes lie on more than one level.
bool HasLevels(const SGraph& graph);
/// The level a room or a plane belongs to: that of the first of its keyframes (-1 if none).
int LevelOfRoom(const SGraph& graph, const Room& room);
int LevelOfPlane(const SGraph& graph, int plane_id);
/// The part of `graph` on `level`: its keyframes and their observations, the planes they
/// observe, the rooms and doorways of its keyframes, its floor. Ids are kept.
SGraph LevelSubgraph(const SGraph& graph, int level);

}  // namespace sgraph
}  // namespace is_graphs
