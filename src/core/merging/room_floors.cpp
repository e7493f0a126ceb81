#include "is_graphs/merging/room_floors.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "is_graphs/sim/room_geometry.h"

namespace is_graphs {
namespace merging {
namespace {

constexpr double kFloorSearch = 0.2;  // m: a keyframe's floor lies this near its height less
                                      // the standing height

}  // namespace

std::optional<double> HeightOfMapFromRoomFloors(const agraph::AGraph& a_graph, int storey,
                                                const sgraph::SGraph& s_graph, int level,
                                                const Eigen::Vector3d& bim_x_map, double standing,
                                                double storey_z, double max_step, double flat,
                                                int count) {
  std::vector<const sgraph::Keyframe*> walked;  // on the level, oldest first
  for (const auto& k : s_graph.keyframes)
    if (level < 0 || k.level == level) walked.push_back(&k);
  std::stable_sort(
      walked.begin(), walked.end(),
      [](const sgraph::Keyframe* a, const sgraph::Keyframe* b) { return a->stamp < b->stamp; });
  // The floor each keyframe observed under it: an upward-facing horizontal plane, the one
  // nearest its height less `standing`.
  std::map<int, const sgraph::Plane*> planes;
  for (const auto& p : s_graph.planes)
    if (p.plane.normal.z() > 0.9) planes[p.id] = &p;
  std::map<int, double> floor_seen;  // keyframe id -> floor height in M
  std::map<int, double> keyframe_z;
  for (const auto* k : walked) keyframe_z[k->id] = k->pose.translation().z() - standing;
  for (const auto& o : s_graph.observations) {
    const auto plane = planes.find(o.plane);
    const auto expected = keyframe_z.find(o.keyframe);
    if (plane == planes.end() || expected == keyframe_z.end()) continue;
    const double h = plane->second->plane.d / plane->second->plane.normal.z();
    if (std::abs(h - expected->second) > kFloorSearch) continue;
    const auto seen = floor_seen.find(o.keyframe);
    if (seen == floor_seen.end() ||
        std::abs(h - expected->second) < std::abs(seen->second - expected->second))
      floor_seen[o.keyframe] = h;
  }
  const double c = std::cos(bim_x_map.z()), s = std::sin(bim_x_map.z());
  std::vector<double> measured, from_height;  // floor seen under the keyframe; its height only
  for (int i = static_cast<int>(walked.size()) - 1;
       i >= 0 && static_cast<int>(measured.size()) < count; --i) {
    const Eigen::Vector3d& p = walked[i]->pose.translation();
    const bool level_before =
        i == 0 || std::abs(walked[i - 1]->pose.translation().z() - p.z()) <= flat;
    const bool level_after = i + 1 == static_cast<int>(walked.size()) ||
                             std::abs(walked[i + 1]->pose.translation().z() - p.z()) <= flat;
    if (!level_before || !level_after) continue;  // on a step or a ramp
    const Eigen::Vector2d in_b(c * p.x() - s * p.y() + bim_x_map.x(),
                               s * p.x() + c * p.y() + bim_x_map.y());
    for (const agraph::Room& room : a_graph.rooms) {
      if (room.storey != storey || room.polygon.size() < 3) continue;
      if (!sim::PointInPolygon(room.polygon, in_b)) continue;
      const auto seen = floor_seen.find(walked[i]->id);
      const bool floor_seen_here = seen != floor_seen.end();
      const double height = room.floor_z - (floor_seen_here ? seen->second : p.z() - standing);
      if (std::abs(height - storey_z) <= max_step) {
        if (floor_seen_here)
          measured.push_back(height);
        else if (static_cast<int>(from_height.size()) < count)
          from_height.push_back(height);
      }
      break;
    }
  }
  std::vector<double>& heights = measured.empty() ? from_height : measured;
  if (heights.empty()) return std::nullopt;
  std::sort(heights.begin(), heights.end());
  const size_t n = heights.size();
  return n % 2 ? heights[n / 2] : 0.5 * (heights[n / 2 - 1] + heights[n / 2]);
}

}  // namespace merging
}  // namespace is_graphs
