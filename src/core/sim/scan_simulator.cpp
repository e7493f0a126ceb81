#include "is_graphs/sim/scan_simulator.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "is_graphs/sim/glass.h"
#include "is_graphs/sim/random.h"
#include "is_graphs/sim/sensor_effects.h"

namespace is_graphs {
namespace sim {

bool RayHitsBox(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                const Eigen::Vector3d& box_min, const Eigen::Vector3d& box_max, double max_s) {
  double lo = 0.0, hi = max_s;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(dir[k]) < 1e-12) {
      if (origin[k] < box_min[k] || origin[k] > box_max[k]) return false;
      continue;
    }
    double a = (box_min[k] - origin[k]) / dir[k];
    double b = (box_max[k] - origin[k]) / dir[k];
    if (a > b) std::swap(a, b);
    lo = std::max(lo, a);
    hi = std::min(hi, b);
    if (lo > hi) return false;
  }
  return true;
}

ScanSimulator::ScanSimulator(const EmbreeScene& scene, const SceneMesh& mesh,
                             const LidarModel& model, const RobotMotion& motion,
                             const Eigen::Isometry3d& base_T_sensor, const BodyBox& body,
                             std::uint64_t seed)
    : scene_(scene),
      mesh_(mesh),
      model_(model),
      motion_(motion),
      base_T_sensor_(base_T_sensor),
      seed_(seed) {
  const int lasers = model_.Lasers();
  const int n = model_.FiringsPerScan() * lasers;
  masked_.assign(n, 0);
  const Eigen::Vector3d box_min = body.center - 0.5 * body.size;
  const Eigen::Vector3d box_max = body.center + 0.5 * body.size;
  const Eigen::Vector3d origin = base_T_sensor_.translation();
  for (int k = 0; k < model_.FiringsPerScan(); ++k) {
    for (int laser = 0; laser < lasers; ++laser) {
      const Eigen::Vector3d dir =
          base_T_sensor_.linear() * model_.Direction(k, laser).cast<double>();
      masked_[k * lasers + laser] =
          RayHitsBox(origin, dir, box_min, box_max, model_.config().max_range) ? 1 : 0;
    }
  }
}

double ScanSimulator::MaskedFraction() const {
  if (masked_.empty()) return 0.0;
  return static_cast<double>(std::count(masked_.begin(), masked_.end(), 1)) / masked_.size();
}

LidarScan ScanSimulator::Simulate(std::uint64_t index, double stamp) const {
  const int firings = model_.FiringsPerScan();
  const int lasers = model_.Lasers();
  // Per-thread scratch buffers: a scan casts 29k (VLP-16) to 66k (OS1-64) rays, reallocating them
  // each time costs page faults. The output does not depend on them.
  thread_local std::vector<Ray> rays;
  thread_local std::vector<int> beam;  // ray -> firing * lasers + laser
  thread_local std::vector<RayHit> hits;
  rays.clear();
  beam.clear();
  const float t_max = static_cast<float>(model_.config().max_range + 1.0);
  for (int k = 0; k < firings; ++k) {
    // One pose per firing sequence; its pulses span at most 48 µs (XT32; VLP-16 35 µs, OS1 0),
    // < 0.06 mm at walking speed, well below the range noise.
    const Eigen::Isometry3d bim_T_sensor =
        motion_.BasePose(stamp + model_.FiringTime(k)) * base_T_sensor_;
    const Eigen::Matrix3f rotation = bim_T_sensor.linear().cast<float>();
    const Eigen::Vector3f origin = bim_T_sensor.translation().cast<float>();
    for (int laser = 0; laser < lasers; ++laser) {
      const int b = k * lasers + laser;
      if (masked_[b]) continue;
      rays.push_back({origin, rotation * model_.Direction(k, laser), t_max});
      beam.push_back(b);
    }
  }
  scene_.Intersect(rays, &hits);
  PassThroughGlass(scene_, mesh_, glass_, rays, &hits, StreamSeed(seed_, kStreamGlass, index));

  // Sensor effects (sensor.effects): what each beam returns instead of its hit, from their own
  // stream; off, the scan is as without them.
  const SensorEffectsConfig& effects = model_.config().effects;
  thread_local std::vector<EffectReturn> returns;
  if (effects.Any()) {
    ApplySensorEffects(scene_, mesh_, effects, rays, hits,
                       StreamSeed(seed_, kStreamSensorEffects, index), &returns);
  }

  // Movers (scene.people, scene.doors), where they stand at each firing's time: a beam that
  // meets one before what it hit (or where it hit nothing) returns off it.
  thread_local std::vector<float> mover_distance;
  thread_local std::vector<Eigen::Vector3f> mover_normal;
  thread_local std::vector<float> mover_reflectivity;
  const bool movers = movers_ && !movers_->empty();
  if (movers) {
    mover_distance.assign(rays.size(), std::numeric_limits<float>::infinity());
    mover_normal.resize(rays.size());
    mover_reflectivity.resize(rays.size());
    std::vector<MovingBody> bodies;
    int firing = -1;
    for (std::size_t i = 0; i < rays.size(); ++i) {
      const int k = beam[i] / lasers;
      if (k != firing) bodies = movers_->BodiesAt(stamp + model_.FiringTime(k)), firing = k;
      const float reach =
          hits[i].triangle >= 0
              ? (effects.Any() ? static_cast<float>(returns[i].distance) : hits[i].distance)
              : rays[i].t_max;
      IntersectBodies(bodies, rays[i], reach, &mover_distance[i], &mover_normal[i],
                      &mover_reflectivity[i]);
    }
  }

  ScanNoise noise(StreamSeed(seed_, kStreamScan, index));
  LidarScan scan;
  scan.stamp = stamp;
  scan.points.reserve(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const RayHit& hit = hits[i];
    const bool on_mover = movers && std::isfinite(mover_distance[i]);
    if (hit.triangle < 0 && !on_mover) continue;
    double distance = 0.0, cos_incidence = 0.0, reflectivity = 0.0;
    bool dropped = false;
    if (on_mover) {
      distance = mover_distance[i];
      cos_incidence = std::abs(mover_normal[i].dot(rays[i].direction));
      reflectivity = mover_reflectivity[i];
    } else if (effects.Any()) {
      distance = returns[i].distance;
      cos_incidence = returns[i].cos_incidence;
      reflectivity = returns[i].reflectivity;
      dropped = returns[i].dropped;
    } else {
      distance = hit.distance;
      cos_incidence = std::abs(hit.normal.dot(rays[i].direction));
      reflectivity = mesh_.reflectivity[hit.triangle];
    }
    const double stddev = effects.range_noise.enabled
                              ? RangeNoiseStddev(effects.range_noise, distance, cos_incidence)
                              : model_.config().range_noise_stddev;
    double range = 0.0;
    if (!model_.Measure(distance, cos_incidence, stddev, noise, &range)) continue;
    const int k = beam[i] / lasers;
    const int laser = beam[i] % lasers;
    const Eigen::Vector3f p = static_cast<float>(range) * model_.Direction(k, laser);
    LidarPoint point;
    point.x = p.x();
    point.y = p.y();
    point.z = p.z();
    point.intensity = model_.Intensity(reflectivity, cos_incidence, noise);
    if (dropped) continue;  // after its draws: a lost return does not shift the others' noise
    point.ring = model_.Ring(laser);
    point.time = static_cast<float>(model_.PulseTime(k, laser));
    point.column = static_cast<std::uint32_t>(k);
    scan.points.push_back(point);
  }
  return scan;
}

}  // namespace sim
}  // namespace is_graphs
