#include "is_graphs/sgraph/plane_segments.h"

#include <algorithm>
#include <utility>

namespace is_graphs {
namespace sgraph {

std::vector<std::vector<int>> SplitCoplanarSegments(const PointList& points,
                                                    const std::vector<int>& inliers,
                                                    const Eigen::Vector3d& direction, double gap) {
  std::vector<std::pair<double, int>> ordered;
  ordered.reserve(inliers.size());
  const Eigen::Vector3f dir = direction.cast<float>();
  for (int i : inliers) ordered.emplace_back(dir.dot(points[i]), i);
  std::sort(ordered.begin(), ordered.end());
  std::vector<std::vector<int>> segments;
  for (size_t k = 0; k < ordered.size(); ++k) {
    if (k == 0 || ordered[k].first - ordered[k - 1].first > gap) segments.emplace_back();
    segments.back().push_back(ordered[k].second);
  }
  return segments;
}

}  // namespace sgraph
}  // namespace is_graphs
