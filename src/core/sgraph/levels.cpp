#include "is_graphs/sgraph/levels.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace is_graphs {
namespace sgraph {

std::string LevelConfig::Validate() const {
  if (!(tolerance > 0.0)) return "level_tolerance: must be > 0 m";
  if (!(min_rise > tolerance)) return "level_min_rise: must be > level_tolerance";
  if (!(settle > 0.0 && settle < tolerance)) return "level_settle: must be in (0, level_tolerance)";
  if (!(landing_length >= 0.0)) return "level_landing_length: must be >= 0 m (0: off)";
  return "";
}

int LevelTracker::Add(const Eigen::Vector3d& position) {
  const double z = position.z();
  if (heights_.empty()) {
    heights_.push_back(z);
    current_ = 0;
  } else if (std::abs(z - heights_[current_]) > config_.tolerance) {
    int near = -1;
    double nearest = 1e300;
    for (int i = 0; i < size(); ++i) {
      const double d = std::abs(z - heights_[i]);
      if (d < nearest) nearest = d, near = i;
    }
    const bool settled = has_last_ && std::abs(z - last_z_) <= config_.settle;
    if (nearest <= config_.tolerance) {
      current_ = near;  // back on a level walked before
      from_ = -1;
    } else if (nearest >= config_.min_rise && settled) {
      from_ = current_;
      heights_.push_back(z);  // off the flight, on a new level
      current_ = size() - 1;
      on_current_ = 0.0;
    } else if (settled && from_ >= 0 && on_current_ < config_.landing_length &&
               (z - heights_[current_]) * (heights_[current_] - heights_[from_]) > 0.0) {
      // The new level was a landing: the climb went on the same way and settled again, as far
      // from every other level as a new level must be. The level moves there.
      bool clear = true;
      for (int i = 0; i < size(); ++i)
        clear = clear && (i == current_ || std::abs(z - heights_[i]) >= config_.min_rise);
      if (clear) heights_[current_] = z, on_current_ = 0.0;
    }  // else on the flight: the level it left
  }
  const double h = heights_[current_];
  if (has_last_ && std::abs(z - h) <= config_.tolerance &&
      std::abs(last_z_ - h) <= config_.tolerance)
    on_current_ += (position.head<2>() - last_xy_).norm();  // walked on it
  last_z_ = z;
  last_xy_ = position.head<2>();
  has_last_ = true;
  return current_;
}

int CurrentLevel(const SGraph& graph) {
  return graph.keyframes.empty() ? 0 : graph.keyframes.back().level;
}

double HeightOffLevel(const SGraph& graph) {
  if (graph.keyframes.empty()) return 0.0;
  const Keyframe& newest = graph.keyframes.back();
  for (const auto& k : graph.keyframes)
    if (k.level == newest.level) return newest.pose.translation().z() - k.pose.translation().z();
  return 0.0;
}

bool OnStair(const SGraph& graph, double tolerance, double settle) {
  if (std::abs(HeightOffLevel(graph)) <= tolerance) return false;
  const size_t n = graph.keyframes.size();
  const double z = graph.keyframes.back().pose.translation().z();
  for (size_t i = n >= 3 ? n - 3 : 0; i + 1 < n; ++i)
    if (std::abs(graph.keyframes[i].pose.translation().z() - z) > settle) return true;
  return false;
}

bool HasLevels(const SGraph& graph) {
  return std::any_of(graph.keyframes.begin(), graph.keyframes.end(),
                     [&](const Keyframe& k) { return k.level != graph.keyframes.front().level; });
}

namespace {

int LevelOfKeyframe(const SGraph& graph, int id) {
  // Keyframes come in id order: a binary search (per room, per snapshot), checked, with a scan
  // for a graph that is not in order.
  const auto it = std::lower_bound(graph.keyframes.begin(), graph.keyframes.end(), id,
                                   [](const Keyframe& k, int value) { return k.id < value; });
  if (it != graph.keyframes.end() && it->id == id) return it->level;
  for (const auto& k : graph.keyframes)
    if (k.id == id) return k.level;
  return -1;
}

}  // namespace

int LevelOfRoom(const SGraph& graph, const Room& room) {
  return room.keyframes.empty() ? -1 : LevelOfKeyframe(graph, room.keyframes.front());
}

int LevelOfPlane(const SGraph& graph, int plane_id) {
  for (const auto& o : graph.observations)
    if (o.plane == plane_id) return LevelOfKeyframe(graph, o.keyframe);
  return -1;
}

SGraph LevelSubgraph(const SGraph& graph, int level) {
  SGraph out;
  out.revision = graph.revision;
  out.stamp = graph.stamp;
  out.odometry_scale = graph.odometry_scale;
  std::set<int> keyframes, planes, rooms;
  for (const auto& k : graph.keyframes) {
    if (k.level != level) continue;
    out.keyframes.push_back(k);
    keyframes.insert(k.id);
  }
  if (!out.keyframes.empty() && !keyframes.count(out.keyframes.front().previous))
    out.keyframes.front().previous = -1;  // the level's walk starts here
  for (const auto& o : graph.observations) {
    if (!keyframes.count(o.keyframe)) continue;
    out.observations.push_back(o);
    planes.insert(o.plane);
  }
  for (const auto& p : graph.planes)
    if (planes.count(p.id)) out.planes.push_back(p);
  for (const auto& r : graph.rooms) {
    if (LevelOfRoom(graph, r) != level) continue;
    out.rooms.push_back(r);
    rooms.insert(r.id);
  }
  for (const auto& f : graph.floors) {
    if (f.id != level) continue;
    out.floors.push_back(f);
    auto& ids = out.floors.back().rooms;
    ids.erase(std::remove_if(ids.begin(), ids.end(), [&](int id) { return !rooms.count(id); }),
              ids.end());
  }
  for (const auto& d : graph.doorways)
    if (!d.keyframes.empty() && keyframes.count(d.keyframes.front())) out.doorways.push_back(d);
  return out;
}

}  // namespace sgraph
}  // namespace is_graphs
