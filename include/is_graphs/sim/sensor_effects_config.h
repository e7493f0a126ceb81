#pragma once

#include <string>

// What a real LiDAR sees that a perfect ray caster does not (a scenario's `sensor.effects`,
// docs/simulator.md; sim/sensor_effects.h applies them). Each effect is off unless its key is
// present (`{}` for the defaults); with all off every scan is as without this struct. The defaults
// come from the VLP-16's data sheet where it gives a figure, else they are the project's choice
// (docs/simulator.md says which is which).

namespace is_graphs {
namespace sim {

/// Range noise growing with range and incidence: sigma = stddev_at_zero + per_metre · range +
/// incidence · (1 / cos(incidence) - 1). Replaces `sensor.range_noise_stddev`.
struct RangeNoiseEffect {
  bool enabled{false};
  double stddev_at_zero{0.012};  // m
  double per_metre{0.0003};      // m per m of range
  double incidence{0.0};         // m at 60 deg from the normal (1 / cos - 1 = 1)
};

/// Mixed pixels: the beam's footprint (exit aperture + divergence) straddling a depth edge. Edge
/// sub-rays are cast at the footprint's left and right (and with `vertical`, top and bottom) rims;
/// when one of them is more than `threshold` from the central range, with `probability` the beam
/// returns a range uniformly between the near and the far one, along its own direction.
struct MixedPixelEffect {
  bool enabled{false};
  double divergence_h_mrad{3.0};  // full angle (VLP-16 data sheet)
  double divergence_v_mrad{1.5};
  double exit_width{0.0095};  // m, the spot at the exit (VLP-16: 9.5 mm x 12.7 mm)
  double exit_height{0.0127};
  bool vertical{false};   // also the top and bottom rims (5 rays a beam instead of 3)
  double threshold{0.3};  // m
  double probability{0.5};
};

/// Dark surfaces: a return is detected with a probability that falls off around the range where
/// reflectivity · cos(incidence) / range² drops to that of `reference_reflectivity` head-on at
/// `reference_range` (a logistic in ln(that range / range), `softness` wide).
struct DarkSurfaceEffect {
  bool enabled{false};
  double reference_range{100.0};  // m
  double reference_reflectivity{0.10};
  double softness{0.1};
};

/// Multi-path ghosts: a downward beam hitting a polished surface (SceneMesh::polished,
/// `scene.polished_floor`) at least `min_incidence_deg` from its normal reflects specularly with
/// `probability`; the return is what the reflected ray hits, at the total path length along the
/// original beam (a mirror image below the floor). Nothing hit: no return.
struct GhostEffect {
  bool enabled{false};
  double min_incidence_deg{60.0};
  double probability{0.2};
};

struct SensorEffectsConfig {
  RangeNoiseEffect range_noise;
  MixedPixelEffect mixed_pixels;
  DarkSurfaceEffect dark_surfaces;
  GhostEffect ghosts;

  bool Any() const {
    return range_noise.enabled || mixed_pixels.enabled || dark_surfaces.enabled || ghosts.enabled;
  }
  /// "" when valid, else "sensor.effects.<effect>.<field>: ..." (the field first).
  std::string Validate() const;
};

}  // namespace sim
}  // namespace is_graphs
