#include "is_graphs/sim/terrain.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>

namespace is_graphs {
namespace sim {
namespace {

std::string At(const Eigen::Vector2d& p, double distance) {
  std::ostringstream out;
  out.precision(2);
  out << std::fixed << "(" << p.x() << ", " << p.y() << "), " << distance << " m along the path";
  return out.str();
}

// A walk's end points, unordered, to the millimetre: the same leg walked back and forth.
std::array<long, 4> LegKey(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  std::array<long, 2> p{std::lround(a.x() * 1e3), std::lround(a.y() * 1e3)};
  std::array<long, 2> q{std::lround(b.x() * 1e3), std::lround(b.y() * 1e3)};
  if (q < p) std::swap(p, q);
  return {p[0], p[1], q[0], q[1]};
}

}  // namespace

std::string TerrainConfig::Validate() const {
  if (!(sample_step > 0.0 && sample_step <= 0.5)) return "sample_step: must be in (0, 0.5] m";
  if (!(max_step > 0.0 && max_step <= 1.0)) return "max_step: must be in (0, 1] m";
  if (!(half_length >= 0.0 && half_length <= 2.0)) return "half_length: must be in [0, 2] m";
  if (!(stair_rise > 0.0)) return "stair_rise: must be > 0 m";
  return "";
}

TerrainProfile TerrainProfile::Flat(double floor_z) {
  TerrainProfile t;
  t.heights_ = {floor_z};
  return t;
}

Result<TerrainProfile> TerrainProfile::Build(const EmbreeScene& scene, const Trajectory& trajectory,
                                             double floor_z, const TerrainConfig& config) {
  using R = Result<TerrainProfile>;
  if (const std::string e = config.Validate(); !e.empty()) return R::Error("terrain: " + e);
  TerrainProfile t;
  t.step_ = config.sample_step;
  t.half_length_ = config.half_length;
  const int n = static_cast<int>(std::ceil(trajectory.PathLength() / t.step_)) + 1;
  t.heights_.reserve(n);
  double z = floor_z;
  const std::vector<Trajectory::Walk> walks = trajectory.Walks();
  if (walks.empty()) {  // standing still: the start's floor
    t.heights_.push_back(z);
    return R::Ok(std::move(t));
  }
  size_t w = 0;
  for (int k = 0; k < n; ++k) {
    const double s = k * t.step_;
    while (w + 1 < walks.size() && walks[w + 1].distance_begin <= s) ++w;
    const Trajectory::Walk& walk = walks[w];
    Eigen::Vector2d p = walk.from;
    const Eigen::Vector2d d = walk.to - walk.from;
    const double length = d.norm();
    if (length > 1e-9) p += std::clamp(s - walk.distance_begin, 0.0, length) / length * d;
    // Down from a step's height above the last ground, twice a step deep.
    const float top = static_cast<float>(z + config.max_step);
    const RayHit hit =
        scene.Intersect(Ray{Eigen::Vector3f(p.x(), p.y(), top), Eigen::Vector3f(0.0f, 0.0f, -1.0f),
                            static_cast<float>(2.0 * config.max_step)});
    if (hit.triangle < 0)
      return R::Error("terrain: no ground within " + std::to_string(config.max_step) +
                      " m of the last at " + At(p, s) + " (a drop, or a hole in the floor)");
    if (std::abs(hit.normal.z()) < 0.7)
      return R::Error("terrain: a wall or a step higher than " + std::to_string(config.max_step) +
                      " m at " + At(p, s));
    z = top - hit.distance;
    t.heights_.push_back(z);
  }
  return R::Ok(std::move(t));
}

double TerrainProfile::GroundAt(double distance) const {
  if (heights_.size() <= 1) return heights_.empty() ? 0.0 : heights_.front();
  const double x = std::clamp(distance / step_, 0.0, static_cast<double>(heights_.size() - 1));
  const size_t i = std::min(static_cast<size_t>(x), heights_.size() - 2);
  const double f = x - static_cast<double>(i);
  return (1.0 - f) * heights_[i] + f * heights_[i + 1];
}

double TerrainProfile::BodyFloor(double distance) const {
  return 0.5 * (GroundAt(distance - half_length_) + GroundAt(distance + half_length_));
}

double TerrainProfile::BodyPitch(double distance) const {
  if (half_length_ <= 0.0) return 0.0;
  const double rise = GroundAt(distance + half_length_) - GroundAt(distance - half_length_);
  return -std::atan2(rise, 2.0 * half_length_);  // front higher: nose up, negative about y
}

double TerrainProfile::HeightChange(double from, double to) const {
  double lo = GroundAt(from), hi = lo;
  for (double s = from; s <= to; s += step_) {
    lo = std::min(lo, GroundAt(s));
    hi = std::max(hi, GroundAt(s));
  }
  return hi - lo;
}

LegSpeed StairLegSpeed(const Trajectory& trajectory, const TerrainProfile& terrain,
                       const TerrainConfig& config, double speed, double stairs_speed) {
  std::map<std::array<long, 4>, double> factor;
  if (!terrain.flat() && speed > 0.0) {
    for (const Trajectory::Walk& w : trajectory.Walks()) {
      const double length = (w.to - w.from).norm();
      if (terrain.HeightChange(w.distance_begin, w.distance_begin + length) > config.stair_rise)
        factor[LegKey(w.from, w.to)] = std::min(1.0, stairs_speed / speed);
    }
  }
  return [factor](const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
    const auto it = factor.find(LegKey(from, to));
    return it == factor.end() ? 1.0 : it->second;
  };
}

}  // namespace sim
}  // namespace is_graphs
