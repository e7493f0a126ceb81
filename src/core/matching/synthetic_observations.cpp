// Observations of a synthetic S-Graph's loose planes: which keyframes had them in view in the
// building as built (for the sight-line evidence, HiddenWalls).
#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <vector>

#include "is_graphs/matching/synthetic_sgraph.h"
#include "is_graphs/matching/wall_crossings.h"

namespace is_graphs {
namespace matching {

void AddSyntheticObservations(const agraph::AGraph& b, const SyntheticSGraphConfig& config,
                              SyntheticSGraph& out) {
  sgraph::SGraph& g = out.graph;
  std::mt19937_64 rng(config.seed ^ 0x0B5E7ull);
  // Interior walls of the taken rooms: two faces, each bounding a room.
  std::set<int> bounding;
  for (const auto& r : b.rooms) bounding.insert(r.surfaces.begin(), r.surfaces.end());
  std::map<int, std::vector<int>> faces;  // wall -> surfaces
  for (const auto& surface : b.surfaces)
    if (surface.wall >= 0) faces[surface.wall].push_back(surface.id);
  std::vector<int> interior;
  for (int rid : config.rooms) {
    if (rid < 0 || rid >= static_cast<int>(b.rooms.size())) continue;
    for (int sid : b.rooms[rid].surfaces) {
      if (sid < 0 || sid >= static_cast<int>(b.surfaces.size())) continue;
      const int wall = b.surfaces[sid].wall;
      if (wall < 0 || faces[wall].size() < 2) continue;
      if (std::all_of(faces[wall].begin(), faces[wall].end(),
                      [&](int f) { return bounding.count(f) > 0; }) &&
          std::find(interior.begin(), interior.end(), wall) == interior.end())
        interior.push_back(wall);
    }
  }
  std::shuffle(interior.begin(), interior.end(), rng);
  for (int k = 0; k < config.unbuilt_walls && k < static_cast<int>(interior.size()); ++k)
    out.unbuilt.push_back(interior[k]);
  agraph::AGraph built = b;
  built.surfaces.erase(std::remove_if(built.surfaces.begin(), built.surfaces.end(),
                                      [&](const agraph::WallSurface& surface) {
                                        return std::count(out.unbuilt.begin(), out.unbuilt.end(),
                                                          surface.wall) > 0;
                                      }),
                       built.surfaces.end());
  const WallCrossings sight(built, 0.4);
  std::set<int> in_rooms;
  for (const auto& r : g.rooms) in_rooms.insert(r.planes.begin(), r.planes.end());
  const Pose2 identity;
  auto to_bim = [&](const Eigen::Vector2d& m) {
    return (out.bim_T_map * Eigen::Vector3d(m.x(), m.y(), 0.0)).head<2>().eval();
  };
  // Each plane is mapped as far as it was seen: its extent is cut to the part of it (in 20
  // pieces) some keyframe had in view.
  constexpr int kPieces = 20;
  for (auto& p : g.planes) {
    const auto truth = out.plane_truth.find(p.id);
    if (in_rooms.count(p.id) || truth == out.plane_truth.end()) continue;
    const int storey = b.surfaces[truth->second].storey;
    const Eigen::Vector2d a = to_bim(p.start), e = to_bim(p.end);
    Eigen::Vector2d n = (out.bim_T_map.linear() * p.plane.normal).head<2>();
    if (n.norm() < 0.5) continue;
    n.normalize();
    int first = kPieces, last = -1;
    for (const auto& k : g.keyframes) {
      const Eigen::Vector2d at = to_bim(k.pose.translation().head<2>());
      if ((0.5 * (a + e) - at).norm() > 10.0) continue;
      bool seen = false;
      for (int i = 0; i < kPieces; ++i) {
        const Eigen::Vector2d q = a + (e - a) * ((i + 0.5) / kPieces) + 0.2 * n;
        if (n.dot(at - q) > 0.0 && !sight.Blocks(at, q, identity, storey)) {
          seen = true;
          first = std::min(first, i), last = std::max(last, i);
        }
      }
      if (seen) g.observations.push_back({k.id, p.id, p.plane, Eigen::Matrix3d::Identity()});
    }
    if (last < 0) continue;
    const Eigen::Vector2d start = p.start, along = p.end - p.start;
    p.start = start + along * (static_cast<double>(first) / kPieces);
    p.end = start + along * (static_cast<double>(last + 1) / kPieces);
  }
}

}  // namespace matching
}  // namespace is_graphs
