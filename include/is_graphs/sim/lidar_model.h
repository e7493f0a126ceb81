#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <random>
#include <vector>

#include "is_graphs/sim/lidar_specs.h"
#include "is_graphs/sim/scenario_config.h"

namespace is_graphs {
namespace sim {

/// The random numbers of one scan: a seeded engine with standard normal and uniform
/// distributions kept across calls (the normal one caches its second variate).
struct ScanNoise {
  explicit ScanNoise(std::uint64_t seed) : rng(seed) {}
  double Normal() { return normal(rng); }
  double Uniform() { return uniform(rng); }
  std::mt19937_64 rng;
  std::normal_distribution<double> normal{0.0, 1.0};
  std::uniform_real_distribution<double> uniform{0.0, 1.0};
};

/// A spinning multi-beam LiDAR's geometry and timing (the beams of `LidarSpec`, the rate and
/// azimuth step of `LidarConfig`). A firing sequence of all lasers repeats every scan period /
/// firings per scan (a "column"); within one, laser i fires spec.laser_interval after laser
/// i - 1 (0: all at once, as the Ouster). The head turns clockwise seen from above: azimuth a
/// (clockwise from +x) is the direction yaw = -a in the sensor's point frame (x forward or, for
/// the Ouster's os_lidar, backward; y left, z up).
class LidarModel {
 public:
  explicit LidarModel(const LidarConfig& config);

  int Lasers() const { return static_cast<int>(spec_.elevation_deg.size()); }
  int FiringsPerScan() const { return firings_; }
  double ScanPeriod() const { return 1.0 / config_.rotation_rate_hz; }
  /// Start of firing sequence `firing` after the scan start, s.
  double FiringTime(int firing) const { return firing * firing_interval_; }
  /// Time of one laser's pulse after the scan start, s.
  double PulseTime(int firing, int laser) const {
    return FiringTime(firing) + laser * spec_.laser_interval;
  }
  /// Unit beam direction in the sensor's point frame.
  const Eigen::Vector3f& Direction(int firing, int laser) const {
    return directions_[static_cast<std::size_t>(firing) * Lasers() + laser];
  }
  /// Elevation (rad) and the driver's ring of a laser id.
  double Elevation(int laser) const;
  std::uint16_t Ring(int laser) const { return spec_.ring[laser]; }

  /// The measured range for a surface at `true_range` hit at incidence cos `cos_incidence`:
  /// false when there is no return (out of range, grazing, dropout), else `range` is set
  /// (Gaussian noise, quantized to the packet's distance unit).
  bool Measure(double true_range, double cos_incidence, ScanNoise& noise, double* range) const {
    return Measure(true_range, cos_incidence, config_.range_noise_stddev, noise, range);
  }
  /// As above with the noise's standard deviation `stddev` (m) instead of the config's.
  bool Measure(double true_range, double cos_incidence, double stddev, ScanNoise& noise,
               double* range) const;
  /// Diffuse intensity on the driver's scale (0..spec.intensity_scale) from reflectivity (0..1)
  /// and incidence.
  float Intensity(double reflectivity, double cos_incidence, ScanNoise& noise) const;

  const LidarConfig& config() const { return config_; }
  const LidarSpec& spec() const { return spec_; }

 private:
  LidarConfig config_;
  LidarSpec spec_;
  int firings_;
  double firing_interval_;
  double cos_max_incidence_;
  std::vector<Eigen::Vector3f> directions_;
};

}  // namespace sim
}  // namespace is_graphs
