#include "is_graphs/sim/vlp16_model.h"

#include <algorithm>
#include <cmath>

namespace is_graphs {
namespace sim {
namespace {
// Laser id -> elevation in degrees (VLP-16 user manual, table 9-1).
constexpr std::array<int, Vlp16Model::kLasers> kElevationDeg{-15, 1, -13, 3,  -11, 5,  -9, 7,
                                                             -7,  9, -5,  11, -3,  13, -1, 15};
}  // namespace

Vlp16Model::Vlp16Model(const Vlp16Config& config)
    : config_(config),
      firings_(static_cast<int>(std::lround(360.0 / config.azimuth_resolution_deg))),
      firing_interval_(1.0 / (config.rotation_rate_hz * firings_)),
      cos_max_incidence_(std::cos(config.max_incidence_deg * M_PI / 180.0)) {
  directions_.resize(static_cast<std::size_t>(firings_) * kLasers);
  for (int k = 0; k < firings_; ++k) {
    const double azimuth = (config_.azimuth_offset_deg + k * 360.0 / firings_) * M_PI / 180.0;
    const double yaw = -azimuth;  // clockwise rotation
    for (int laser = 0; laser < kLasers; ++laser) {
      const double el = Elevation(laser);
      directions_[static_cast<std::size_t>(k) * kLasers + laser] =
          Eigen::Vector3d(std::cos(el) * std::cos(yaw), std::cos(el) * std::sin(yaw), std::sin(el))
              .cast<float>();
    }
  }
}

double Vlp16Model::Elevation(int laser) const { return kElevationDeg[laser] * M_PI / 180.0; }

std::uint16_t Vlp16Model::Ring(int laser) const {
  return static_cast<std::uint16_t>((kElevationDeg[laser] + 15) / 2);
}

bool Vlp16Model::Measure(double true_range, double cos_incidence, ScanNoise& noise,
                         double* range) const {
  if (!(true_range >= config_.min_range && true_range <= config_.max_range)) return false;
  if (cos_incidence < cos_max_incidence_) return false;
  if (config_.dropout_probability > 0.0 && noise.Uniform() < config_.dropout_probability) {
    return false;
  }
  double r = true_range;
  if (config_.range_noise_stddev > 0.0) {
    r += config_.range_noise_stddev * noise.Normal();
  }
  if (config_.range_resolution > 0.0) {
    r = std::round(r / config_.range_resolution) * config_.range_resolution;
  }
  if (r < config_.min_range || r > config_.max_range) return false;
  *range = r;
  return true;
}

float Vlp16Model::Intensity(double reflectivity, double cos_incidence, ScanNoise& noise) const {
  double value = 100.0 * reflectivity * cos_incidence;
  if (config_.intensity_noise_stddev > 0.0) {
    value += config_.intensity_noise_stddev * noise.Normal();
  }
  return static_cast<float>(std::round(std::clamp(value, 0.0, 100.0)));
}

}  // namespace sim
}  // namespace is_graphs
