#include "is_graphs/sim/lidar_model.h"

#include <algorithm>
#include <cmath>

namespace is_graphs {
namespace sim {

LidarModel::LidarModel(const LidarConfig& config)
    : config_(config),
      spec_(SpecFor(config.model)),
      firings_(static_cast<int>(std::lround(360.0 / config.azimuth_resolution_deg))),
      firing_interval_(1.0 / (config.rotation_rate_hz * firings_)),
      cos_max_incidence_(std::cos(config.max_incidence_deg * M_PI / 180.0)) {
  const int lasers = Lasers();
  directions_.resize(static_cast<std::size_t>(firings_) * lasers);
  for (int k = 0; k < firings_; ++k) {
    const double azimuth = (config_.azimuth_offset_deg + k * 360.0 / firings_) * M_PI / 180.0;
    const double yaw = -azimuth;  // clockwise rotation
    for (int laser = 0; laser < lasers; ++laser) {
      const double el = Elevation(laser);
      directions_[static_cast<std::size_t>(k) * lasers + laser] =
          Eigen::Vector3d(std::cos(el) * std::cos(yaw), std::cos(el) * std::sin(yaw), std::sin(el))
              .cast<float>();
    }
  }
}

double LidarModel::Elevation(int laser) const { return spec_.elevation_deg[laser] * M_PI / 180.0; }

bool LidarModel::Measure(double true_range, double cos_incidence, double stddev, ScanNoise& noise,
                         double* range) const {
  if (!(true_range >= config_.min_range && true_range <= config_.max_range)) return false;
  if (cos_incidence < cos_max_incidence_) return false;
  if (config_.dropout_probability > 0.0 && noise.Uniform() < config_.dropout_probability) {
    return false;
  }
  double r = true_range;
  if (stddev > 0.0) r += stddev * noise.Normal();
  if (config_.range_resolution > 0.0) {
    r = std::round(r / config_.range_resolution) * config_.range_resolution;
  }
  if (r < config_.min_range || r > config_.max_range) return false;
  *range = r;
  return true;
}

float LidarModel::Intensity(double reflectivity, double cos_incidence, ScanNoise& noise) const {
  const double scale = spec_.intensity_scale;
  double value = scale * reflectivity * cos_incidence;
  if (config_.intensity_noise_stddev > 0.0) {
    value += config_.intensity_noise_stddev * noise.Normal();
  }
  return static_cast<float>(std::round(std::clamp(value, 0.0, scale)));
}

}  // namespace sim
}  // namespace is_graphs
