#include "is_graphs/sim/sensor_effects.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include "is_graphs/sim/random.h"

namespace is_graphs {
namespace sim {
namespace {

// "sensor.effects.<field>: must be in [lo, hi], got v" when !(lo <= v <= hi) (NaN fails); with
// `open_lo`, lo itself fails too.
std::string Check(const std::string& field, double v, double lo, double hi, bool open_lo = false) {
  if (v >= lo && v <= hi && !(open_lo && v == lo)) return "";
  std::ostringstream e;
  e << "sensor.effects." << field << ": must be in " << (open_lo ? "(" : "[") << lo << ", " << hi
    << "], got " << v;
  return e.str();
}

// Sub-streams of the scan's effects stream (random.h kStreamSensorEffects).
constexpr std::uint64_t kMixed = 1, kGhost = 2, kDark = 3;

// The footprint's rim rays of beam `ray`: origin shifted by half the exit spot, direction turned
// by half the divergence, sideways (h) and, with `vertical`, up and down (v).
void RimRays(const MixedPixelEffect& e, const Ray& ray, std::vector<Ray>* out) {
  const Eigen::Vector3f& d = ray.direction;
  Eigen::Vector3f h = d.cross(Eigen::Vector3f::UnitZ());
  if (h.norm() < 1e-6f) h = Eigen::Vector3f::UnitX();
  h.normalize();
  const Eigen::Vector3f v = h.cross(d).normalized();
  const float th = static_cast<float>(std::tan(0.5e-3 * e.divergence_h_mrad));
  const float tv = static_cast<float>(std::tan(0.5e-3 * e.divergence_v_mrad));
  const float wh = static_cast<float>(0.5 * e.exit_width);
  const float wv = static_cast<float>(0.5 * e.exit_height);
  for (float s : {-1.0f, 1.0f}) {
    out->push_back({ray.origin + s * wh * h, (d + s * th * h).normalized(), ray.t_max});
  }
  if (!e.vertical) return;
  for (float s : {-1.0f, 1.0f}) {
    out->push_back({ray.origin + s * wv * v, (d + s * tv * v).normalized(), ray.t_max});
  }
}

void MixPixels(const EmbreeScene& scene, const SceneMesh& mesh, const MixedPixelEffect& e,
               const std::vector<Ray>& rays, const std::vector<RayHit>& hits, std::uint64_t seed,
               std::vector<EffectReturn>* out, std::vector<std::uint8_t>* mixed) {
  const int per_beam = e.vertical ? 4 : 2;
  std::vector<Ray> rims;
  std::vector<int> beam;
  rims.reserve(rays.size() * per_beam);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    if (hits[i].triangle < 0) continue;
    RimRays(e, rays[i], &rims);
    beam.push_back(static_cast<int>(i));
  }
  std::vector<RayHit> rim_hits;
  scene.Intersect(rims, &rim_hits);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (std::size_t k = 0; k < beam.size(); ++k) {
    const double u = uniform(rng), f = uniform(rng);  // two draws a hit beam, whatever it does
    const int i = beam[k];
    const double centre = hits[i].distance;
    double edge = centre;
    for (int j = 0; j < per_beam; ++j) {
      const RayHit& r = rim_hits[k * per_beam + j];
      if (r.triangle < 0 || (!mesh.glass.empty() && mesh.glass[r.triangle])) continue;
      if (std::abs(r.distance - centre) > std::abs(edge - centre)) edge = r.distance;
    }
    if (std::abs(edge - centre) <= e.threshold || u >= e.probability) continue;
    const double near = std::min(centre, edge), far = std::max(centre, edge);
    (*out)[i].distance = near + f * (far - near);
    (*mixed)[i] = 1;
  }
}

void Ghosts(const EmbreeScene& scene, const SceneMesh& mesh, const GhostEffect& e,
            const std::vector<Ray>& rays, const std::vector<RayHit>& hits, std::uint64_t seed,
            const std::vector<std::uint8_t>& mixed, std::vector<EffectReturn>* out) {
  if (mesh.polished.empty()) return;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const double cos_max = std::cos(e.min_incidence_deg * M_PI / 180.0);
  std::vector<Ray> mirrored;
  std::vector<int> beam;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const double u = uniform(rng);  // one draw a ray
    const RayHit& hit = hits[i];
    if (hit.triangle < 0 || !mesh.polished[hit.triangle] || mixed[i]) continue;
    const Eigen::Vector3f& d = rays[i].direction;
    Eigen::Vector3f n = hit.normal;
    if (n.dot(d) > 0.0f) n = -n;                   // towards the sensor
    if (d.z() >= 0.0f || n.z() <= 0.0f) continue;  // a floor seen from above
    if (-n.dot(d) > cos_max || u >= e.probability) continue;
    const float left = rays[i].t_max - hit.distance;
    if (left <= 0.0f) continue;
    const Eigen::Vector3f p = rays[i].origin + hit.distance * d + 1e-3f * n;
    mirrored.push_back({p, (d - 2.0f * d.dot(n) * n).normalized(), left});
    beam.push_back(static_cast<int>(i));
  }
  std::vector<RayHit> second;
  scene.Intersect(mirrored, &second);
  for (std::size_t k = 0; k < beam.size(); ++k) {
    EffectReturn& r = (*out)[beam[k]];
    if (second[k].triangle < 0) {
      r.dropped = true;  // mirrored away: no echo
      continue;
    }
    r.distance = hits[beam[k]].distance + second[k].distance;
    r.cos_incidence = std::abs(second[k].normal.dot(mirrored[k].direction));
    r.reflectivity = mesh.reflectivity[second[k].triangle];
  }
}

}  // namespace

std::string SensorEffectsConfig::Validate() const {
  const RangeNoiseEffect& n = range_noise;
  const MixedPixelEffect& m = mixed_pixels;
  const DarkSurfaceEffect& d = dark_surfaces;
  for (const std::string& e :
       {Check("range_noise.stddev_at_zero", n.stddev_at_zero, 0.0, 1.0),
        Check("range_noise.per_metre", n.per_metre, 0.0, 0.1),
        Check("range_noise.incidence", n.incidence, 0.0, 1.0),
        Check("mixed_pixels.divergence_h_mrad", m.divergence_h_mrad, 0.0, 100.0),
        Check("mixed_pixels.divergence_v_mrad", m.divergence_v_mrad, 0.0, 100.0),
        Check("mixed_pixels.exit_width", m.exit_width, 0.0, 0.5),
        Check("mixed_pixels.exit_height", m.exit_height, 0.0, 0.5),
        Check("mixed_pixels.threshold", m.threshold, 0.0, 100.0, true),
        Check("mixed_pixels.probability", m.probability, 0.0, 1.0),
        Check("dark_surfaces.reference_range", d.reference_range, 0.0, 1000.0, true),
        Check("dark_surfaces.reference_reflectivity", d.reference_reflectivity, 0.0, 1.0, true),
        Check("dark_surfaces.softness", d.softness, 0.0, 1.0, true),
        Check("ghosts.min_incidence_deg", ghosts.min_incidence_deg, 0.0, 90.0),
        Check("ghosts.probability", ghosts.probability, 0.0, 1.0)}) {
    if (!e.empty()) return e;
  }
  return "";
}

double RangeNoiseStddev(const RangeNoiseEffect& e, double range, double cos_incidence) {
  const double c = std::max(cos_incidence, 1e-3);
  return e.stddev_at_zero + e.per_metre * range + e.incidence * (1.0 / c - 1.0);
}

double DetectionProbability(const DarkSurfaceEffect& e, double reflectivity, double cos_incidence,
                            double range) {
  const double echo = reflectivity * std::max(cos_incidence, 0.0);
  if (echo <= 0.0) return 0.0;
  if (range <= 0.0) return 1.0;
  // The range at which this surface's echo is the reference's at its range (echo ∝ ρ cos / r²).
  const double reach = e.reference_range * std::sqrt(echo / e.reference_reflectivity);
  return 1.0 / (1.0 + std::exp(-std::log(reach / range) / e.softness));
}

void ApplySensorEffects(const EmbreeScene& scene, const SceneMesh& mesh,
                        const SensorEffectsConfig& config, const std::vector<Ray>& rays,
                        const std::vector<RayHit>& hits, std::uint64_t seed,
                        std::vector<EffectReturn>* returns) {
  returns->resize(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    EffectReturn& r = (*returns)[i];
    const RayHit& hit = hits[i];
    r = EffectReturn{};
    if (hit.triangle < 0) continue;
    r.distance = hit.distance;
    r.cos_incidence = std::abs(hit.normal.dot(rays[i].direction));
    r.reflectivity = mesh.reflectivity[hit.triangle];
  }
  std::vector<std::uint8_t> mixed(rays.size(), 0);
  if (config.mixed_pixels.enabled)
    MixPixels(scene, mesh, config.mixed_pixels, rays, hits, StreamSeed(seed, kMixed), returns,
              &mixed);
  if (config.ghosts.enabled)
    Ghosts(scene, mesh, config.ghosts, rays, hits, StreamSeed(seed, kGhost), mixed, returns);
  if (!config.dark_surfaces.enabled) return;
  std::mt19937_64 rng(StreamSeed(seed, kDark));
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const double u = uniform(rng);  // one draw a ray
    EffectReturn& r = (*returns)[i];
    if (hits[i].triangle < 0 || r.dropped) continue;
    if (u >=
        DetectionProbability(config.dark_surfaces, r.reflectivity, r.cos_incidence, r.distance))
      r.dropped = true;
  }
}

}  // namespace sim
}  // namespace is_graphs
