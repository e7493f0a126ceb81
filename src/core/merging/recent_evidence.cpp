#include "is_graphs/merging/recent_evidence.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "is_graphs/agraph/agraph_queries.h"

namespace is_graphs {
namespace merging {
namespace {

constexpr double kExtentMargin = 1.0;  // m beyond a wall-surface's ends

// On the storey walked (-1: any), as the robot's height in B says: a wall seen on the first
// floor is not supported by the ground floor's.
bool Supported(const agraph::AGraph& a_graph, const geometry::Plane& plane_b,
               const Eigen::Vector3d& middle_b, int storey, const MergerConfig& config) {
  const double cos_gate = std::cos(config.gate_angle_deg * M_PI / 180.0);
  for (const auto& s : a_graph.surfaces) {
    if (storey >= 0 && s.storey != storey) continue;
    if (s.plane.normal.dot(plane_b.normal) < cos_gate) continue;
    if (std::abs(s.plane.SignedDistance(middle_b)) > config.gate_offset) continue;
    const Eigen::Vector2d t = s.Tangent().head<2>();
    const double along = t.dot(middle_b.head<2>() - s.start);
    if (along < -kExtentMargin || along > s.Length() + kExtentMargin) continue;
    return true;
  }
  return false;
}

}  // namespace

RecentEvidence CheckRecentEvidence(const agraph::AGraph& a_graph, const sgraph::SGraph& s_graph,
                                   const MergeSolution& solution, const MergerConfig& config) {
  RecentEvidence out;
  if (s_graph.keyframes.empty() || config.recent_keyframes <= 0) return out;
  std::vector<const sgraph::Keyframe*> order;
  for (const auto& k : s_graph.keyframes) order.push_back(&k);
  std::sort(order.begin(), order.end(), [](const sgraph::Keyframe* a, const sgraph::Keyframe* b) {
    return a->stamp > b->stamp;
  });
  std::map<int, const sgraph::Keyframe*> recent;
  for (size_t i = 0; i < order.size() && static_cast<int>(i) < config.recent_keyframes; ++i)
    recent[order[i]->id] = order[i];
  std::map<int, const sgraph::Plane*> planes;
  for (const auto& p : s_graph.planes) planes[p.id] = &p;
  const Eigen::Isometry3d bim_T_map = solution.BimTMap();
  std::set<int> seen, supported;
  for (const auto& o : s_graph.observations) {
    const auto k = recent.find(o.keyframe);
    const auto p = planes.find(o.plane);
    if (k == recent.end() || p == planes.end()) continue;
    const sgraph::Plane& plane = *p->second;
    if (std::abs(plane.plane.normal.z()) > 0.3) continue;  // walls only
    if ((plane.end - plane.start).norm() < config.recent_min_length) continue;
    seen.insert(plane.id);
    const auto merged = solution.keyframes.find(o.keyframe);
    const Eigen::Isometry3d& map_T_k =
        merged != solution.keyframes.end() ? merged->second : k->second->pose;
    const Eigen::Isometry3d bim_T_k = bim_T_map * map_T_k;
    const geometry::Plane in_b = o.local.Transformed(bim_T_k);
    // The middle of the plane's mapped extent, at the keyframe's height, moved into B.
    const Eigen::Vector2d mid_m = 0.5 * (plane.start + plane.end);
    Eigen::Vector3d middle_b =
        bim_T_map * Eigen::Vector3d(mid_m.x(), mid_m.y(), map_T_k.translation().z());
    middle_b = in_b.Project(middle_b);
    const int storey = agraph::StoreyAtHeight(a_graph, bim_T_k.translation().z());
    if (Supported(a_graph, in_b, middle_b, storey, config)) supported.insert(plane.id);
  }
  out.planes = static_cast<int>(seen.size());
  out.supported = static_cast<int>(supported.size());
  std::ostringstream m;
  m << out.supported << " of the " << out.planes << " walls seen in the last "
    << config.recent_keyframes << " keyframes lie on the BIM's wall-surfaces";
  out.message = m.str();
  out.contradicts = out.planes >= config.recent_min_planes &&
                    out.supported < config.recent_min_support * out.planes;
  return out;
}

}  // namespace merging
}  // namespace is_graphs
