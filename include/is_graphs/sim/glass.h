#pragma once

#include <cstdint>
#include <vector>

#include "is_graphs/sim/embree_scene.h"
#include "is_graphs/sim/scene.h"

namespace is_graphs {
namespace sim {

/// Glass (GlassConfig, scenario_config.h). After `scene.Intersect(rays, hits)`: each hit on a
/// glass triangle (mesh.glass) either stays (a return off the pane) or is cast on from just behind
/// the pane, its distance counted from the ray's origin. Decisions draw from a generator seeded
/// with `seed`, in ray order (deterministic). Nothing happens when `config.enabled` is false or the
/// mesh has no glass.
void PassThroughGlass(const EmbreeScene& scene, const SceneMesh& mesh, const GlassConfig& config,
                      const std::vector<Ray>& rays, std::vector<RayHit>* hits, std::uint64_t seed);

}  // namespace sim
}  // namespace is_graphs
