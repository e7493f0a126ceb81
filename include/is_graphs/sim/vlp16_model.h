#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <random>
#include <vector>

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

/// The Velodyne VLP-16 geometry and timing. Lasers fire in the order of the data sheet (laser
/// id 0..15 at -15°, +1°, -13°, +3°, ... +15°), 2.304 µs apart; a firing sequence of all 16
/// repeats every scan period / firings per scan (55.6 µs at 10 Hz, 0.2°). The head turns
/// clockwise seen from above: azimuth a (clockwise from +x) is the direction yaw = -a in the
/// `velodyne` frame (x forward, y left, z up). `ring` is the driver's: 0 for the lowest beam.
class Vlp16Model {
 public:
  static constexpr int kLasers = 16;
  static constexpr double kLaserInterval = 2.304e-6;  // s between two lasers of a sequence

  explicit Vlp16Model(const Vlp16Config& config);

  int FiringsPerScan() const { return firings_; }
  double ScanPeriod() const { return 1.0 / config_.rotation_rate_hz; }
  /// Start of firing sequence `firing` after the scan start, s.
  double FiringTime(int firing) const { return firing * firing_interval_; }
  /// Time of one laser's pulse after the scan start, s.
  double PulseTime(int firing, int laser) const {
    return FiringTime(firing) + laser * kLaserInterval;
  }
  /// Unit beam direction in the velodyne frame.
  const Eigen::Vector3f& Direction(int firing, int laser) const {
    return directions_[static_cast<std::size_t>(firing) * kLasers + laser];
  }
  /// Elevation (rad) and ring of a laser id.
  double Elevation(int laser) const;
  std::uint16_t Ring(int laser) const;

  /// The measured range for a surface at `true_range` hit at incidence cos `cos_incidence`:
  /// false when there is no return (out of range, grazing, dropout), else `range` is set
  /// (Gaussian noise, quantized to the packet's 2 mm unit).
  bool Measure(double true_range, double cos_incidence, ScanNoise& noise, double* range) const;
  /// Diffuse intensity on the 0..100 scale from reflectivity (0..1) and incidence.
  float Intensity(double reflectivity, double cos_incidence, ScanNoise& noise) const;

  const Vlp16Config& config() const { return config_; }

 private:
  Vlp16Config config_;
  int firings_;
  double firing_interval_;
  double cos_max_incidence_;
  std::vector<Eigen::Vector3f> directions_;
};

}  // namespace sim
}  // namespace is_graphs
