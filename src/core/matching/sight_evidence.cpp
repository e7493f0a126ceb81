#include "is_graphs/matching/sight_evidence.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace is_graphs {
namespace matching {
namespace {

constexpr double kSampleSpacing = 0.3;  // m along a plane
constexpr int kMaxSamples = 16;
constexpr double kStandOff = 0.2;  // m in front of the plane: its own wall does not block

}  // namespace

std::vector<SeenWall> SeenFrom(const sgraph::SGraph& graph, const std::vector<WallSegment>& walls,
                               int max_viewpoints) {
  std::map<int, Eigen::Vector2d> keyframe_at;
  for (const auto& k : graph.keyframes)
    if (k.pose.translation().allFinite()) keyframe_at.emplace(k.id, k.pose.translation().head<2>());
  std::map<int, std::vector<Eigen::Vector2d>> seen;  // plane id -> viewpoints, in order
  for (const auto& o : graph.observations) {
    const auto k = keyframe_at.find(o.keyframe);
    if (k != keyframe_at.end()) seen[o.plane].push_back(k->second);
  }
  std::vector<SeenWall> out;
  for (const auto& w : walls) {
    const auto it = seen.find(w.id);
    if (it == seen.end() || it->second.empty() || max_viewpoints <= 0) continue;
    const auto& all = it->second;
    SeenWall s{w, {}};
    const int n = std::min<int>(max_viewpoints, static_cast<int>(all.size()));
    for (int i = 0; i < n; ++i)
      s.from.push_back(all[static_cast<size_t>(i) * all.size() / static_cast<size_t>(n)]);
    out.push_back(std::move(s));
  }
  return out;
}

double HiddenWalls(const std::vector<SeenWall>& walls, const WallCrossings& crossings,
                   const Pose2& pose, int storey, double full_length) {
  double hidden = 0.0;
  for (const auto& s : walls) {
    const WallSegment& w = s.wall;
    const int samples =
        std::clamp(static_cast<int>(std::ceil(w.length / kSampleSpacing)), 1, kMaxSamples);
    int blocked = 0;
    for (int i = 0; i < samples; ++i) {
      const Eigen::Vector2d target =
          w.a + (w.b - w.a) * ((i + 0.5) / samples) + kStandOff * w.normal;
      if (std::all_of(s.from.begin(), s.from.end(), [&](const Eigen::Vector2d& from) {
            return crossings.Blocks(from, target, pose, storey);
          }))
        ++blocked;
    }
    hidden += std::min(1.0, w.length / full_length) * blocked / samples;
  }
  return hidden;
}

}  // namespace matching
}  // namespace is_graphs
