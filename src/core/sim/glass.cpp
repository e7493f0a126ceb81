#include "is_graphs/sim/glass.h"

#include <cmath>
#include <limits>
#include <random>
#include <sstream>

#include "is_graphs/sim/scene.h"

namespace is_graphs {
namespace sim {

std::string GlassConfig::Validate() const {
  std::ostringstream e;
  if (!(return_probability >= 0.0 && return_probability <= 1.0))
    e << "scene.glass.return_probability: must be in [0, 1], got " << return_probability;
  else if (!(return_max_angle_deg >= 0.0 && return_max_angle_deg <= 90.0))
    e << "scene.glass.return_max_angle_deg: must be in [0, 90] deg, got " << return_max_angle_deg;
  else if (max_layers < 1 || max_layers > 64)
    e << "scene.glass.max_layers: must be in [1, 64], got " << max_layers;
  else if (enabled && classes.empty())
    e << "scene.glass.classes: must name at least one IFC class";
  return e.str();
}

bool GlassConfig::IsGlass(const std::string& ifc_class) const {
  const std::string suffix = "StandardCase";
  for (const std::string& c : classes) {
    if (ifc_class == c || ifc_class == c + suffix) return true;
  }
  return false;
}

void PassThroughGlass(const EmbreeScene& scene, const SceneMesh& mesh, const GlassConfig& config,
                      const std::vector<Ray>& rays, std::vector<RayHit>* hits, std::uint64_t seed) {
  if (!config.enabled || mesh.glass.empty()) return;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const double cos_return = std::cos(config.return_max_angle_deg * M_PI / 180.0);
  constexpr float kStep = 1e-3f;  // m past the pane: the next cast does not hit it again
  std::vector<int> todo;          // rays whose (absolute) hit is a pane
  for (std::size_t i = 0; i < hits->size(); ++i) {
    const int t = (*hits)[i].triangle;
    if (t >= 0 && mesh.glass[t]) todo.push_back(static_cast<int>(i));
  }
  std::vector<Ray> on;
  std::vector<RayHit> next;
  std::vector<int> cast;
  std::vector<float> starts;  // each cast's distance from the ray's origin
  for (int layer = 0; layer < config.max_layers && !todo.empty(); ++layer) {
    on.clear();
    cast.clear();
    starts.clear();
    for (int i : todo) {
      RayHit& hit = (*hits)[i];
      const double cos_incidence = std::abs(hit.normal.dot(rays[i].direction));
      // One draw per pane hit, whatever the incidence: a beam's fate does not shift the others'.
      const double u = uniform(rng);
      if (cos_incidence >= cos_return && u < config.return_probability) continue;  // off the pane
      const float start = hit.distance + kStep;
      if (start >= rays[i].t_max) {
        hit = RayHit{std::numeric_limits<float>::infinity(), hit.normal, -1};
        continue;
      }
      on.push_back(
          {rays[i].origin + start * rays[i].direction, rays[i].direction, rays[i].t_max - start});
      cast.push_back(i);
      starts.push_back(start);
    }
    scene.Intersect(on, &next);
    todo.clear();
    for (std::size_t k = 0; k < cast.size(); ++k) {
      RayHit& hit = (*hits)[cast[k]];
      hit = next[k];
      if (hit.triangle < 0) continue;
      hit.distance += starts[k];  // from the ray's origin again
      if (mesh.glass[hit.triangle]) todo.push_back(cast[k]);
    }
  }
  // A beam still on a pane after max_layers returns off that pane.
}

}  // namespace sim
}  // namespace is_graphs
