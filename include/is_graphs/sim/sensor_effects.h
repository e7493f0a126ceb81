#pragma once

#include <cstdint>
#include <vector>

#include "is_graphs/sim/embree_scene.h"
#include "is_graphs/sim/scene.h"
#include "is_graphs/sim/sensor_effects_config.h"

namespace is_graphs {
namespace sim {

/// What a beam returns once the sensor effects have acted on its hit (distance along the beam
/// from its origin, the surface's incidence cos and reflectivity), or `dropped`.
struct EffectReturn {
  double distance{0.0};
  double cos_incidence{1.0};
  double reflectivity{0.0};
  bool dropped{false};
};

/// sigma of the range noise (RangeNoiseEffect) at `range` and incidence cos `cos_incidence`.
double RangeNoiseStddev(const RangeNoiseEffect& e, double range, double cos_incidence);
/// Probability that a return off a surface of `reflectivity` at `range`, `cos_incidence` is
/// detected (DarkSurfaceEffect): 0.5 where its echo is the reference target's at its range.
double DetectionProbability(const DarkSurfaceEffect& e, double reflectivity, double cos_incidence,
                            double range);

/// After the scan's `scene.Intersect(rays, hits)` (and glass): each ray's return under the
/// mixed pixels, ghosts and dark surfaces of `config` (range noise is the LidarModel's). Rays
/// that hit nothing stay so. Each effect draws from its own generator, seeded from `seed` and the
/// effect, a fixed number of variates per ray in ray order (deterministic; one beam's fate does
/// not shift another's).
void ApplySensorEffects(const EmbreeScene& scene, const SceneMesh& mesh,
                        const SensorEffectsConfig& config, const std::vector<Ray>& rays,
                        const std::vector<RayHit>& hits, std::uint64_t seed,
                        std::vector<EffectReturn>* returns);

}  // namespace sim
}  // namespace is_graphs
