#include "is_graphs/sgraph/backend_window.h"

#include <algorithm>
#include <map>
#include <unordered_set>

namespace is_graphs {
namespace sgraph {

void SelectWindow(const std::vector<Keyframe>& keyframes,
                  const std::vector<PlaneObservation>& observations, const BackendConfig& config,
                  BackendProblem& problem) {
  problem.constant_keyframes.clear();
  problem.constant_planes.clear();
  problem.constant_rooms.clear();
  problem.constant_floor = false;
  const size_t window = static_cast<size_t>(std::max(0, config.window_keyframes));
  if (window == 0 || keyframes.size() <= window) {
    problem.keyframes = keyframes;
    problem.observations = observations;
    return;
  }
  const size_t first = keyframes.size() - window;
  const int first_id = keyframes[first].id;  // ids grow: the window is every id >= first_id

  std::unordered_set<int> moved_planes;
  for (const auto& o : observations)
    if (o.keyframe >= first_id) moved_planes.insert(o.plane);
  // Observations kept: the window's, and the newest anchors of each moved plane (observations
  // are appended keyframe by keyframe: the newest are last).
  std::vector<size_t> kept;
  std::map<int, int> anchors_of;  // plane id -> older observations kept
  std::unordered_set<int> held;   // keyframe ids
  for (size_t i = observations.size(); i-- > 0;) {
    const PlaneObservation& o = observations[i];
    if (o.keyframe >= first_id) {
      kept.push_back(i);
    } else if (moved_planes.count(o.plane) && anchors_of[o.plane]++ < config.window_plane_anchors) {
      kept.push_back(i);
      held.insert(o.keyframe);
    }
  }
  if (keyframes[first].previous >= 0) held.insert(keyframes[first].previous);
  std::reverse(kept.begin(), kept.end());

  problem.keyframes.clear();
  problem.observations.clear();
  for (size_t i = 0; i < first; ++i)
    if (held.count(keyframes[i].id)) problem.keyframes.push_back(keyframes[i]);
  problem.keyframes.insert(problem.keyframes.end(), keyframes.begin() + first, keyframes.end());
  for (int id : held) problem.constant_keyframes.insert(id);
  problem.observations.reserve(kept.size());
  for (size_t i : kept) problem.observations.push_back(observations[i]);

  // A room moves with any of its planes; its other planes are held. The floor moves with a room.
  bool floor_moves = false;
  for (const auto& r : problem.rooms) {
    const bool moves = std::any_of(r.planes.begin(), r.planes.end(),
                                   [&](int id) { return moved_planes.count(id) > 0; });
    if (!moves) {
      problem.constant_rooms.insert(r.id);
      continue;
    }
    floor_moves = true;
    for (int id : r.planes)
      if (!moved_planes.count(id)) problem.constant_planes.insert(id);
  }
  problem.constant_floor = !floor_moves;
}

}  // namespace sgraph
}  // namespace is_graphs
