// The `sensor.effects` section of a scenario YAML: range noise, mixed pixels, dark surfaces and
// multi-path ghosts (sensor_effects_config.h). A present effect key (even `{}`) turns it on.
#include "yaml_fields.h"

namespace is_graphs {
namespace sim {
namespace yaml_fields {
namespace {

// The effect's map, or an invalid node when absent; `enabled` set when present.
YAML::Node Effect(const YAML::Node& n, const std::string& f, const char* key,
                  const std::set<std::string>& fields, bool* enabled) {
  const YAML::Node e = n[key];
  if (!e) return e;
  if (!e.IsMap()) Fail(Join(f, key), "must be a map ({} for the defaults)");
  CheckMap(e, Join(f, key), fields);
  *enabled = true;
  return e;
}

}  // namespace

void ParseSensorEffects(const YAML::Node& n, SensorEffectsConfig* s) {
  const std::string f = "sensor.effects";
  CheckMap(n, f, {"range_noise", "mixed_pixels", "dark_surfaces", "ghosts"});
  RangeNoiseEffect& r = s->range_noise;
  if (const YAML::Node e =
          Effect(n, f, "range_noise", {"stddev_at_zero", "per_metre", "incidence"}, &r.enabled)) {
    const std::string ef = f + ".range_noise";
    Get(e, ef, "stddev_at_zero", &r.stddev_at_zero);
    Get(e, ef, "per_metre", &r.per_metre);
    Get(e, ef, "incidence", &r.incidence);
  }
  MixedPixelEffect& m = s->mixed_pixels;
  if (const YAML::Node e = Effect(n, f, "mixed_pixels",
                                  {"divergence_h_mrad", "divergence_v_mrad", "exit_width",
                                   "exit_height", "vertical", "threshold", "probability"},
                                  &m.enabled)) {
    const std::string ef = f + ".mixed_pixels";
    Get(e, ef, "divergence_h_mrad", &m.divergence_h_mrad);
    Get(e, ef, "divergence_v_mrad", &m.divergence_v_mrad);
    Get(e, ef, "exit_width", &m.exit_width);
    Get(e, ef, "exit_height", &m.exit_height);
    Get(e, ef, "vertical", &m.vertical);
    Get(e, ef, "threshold", &m.threshold);
    Get(e, ef, "probability", &m.probability);
  }
  DarkSurfaceEffect& d = s->dark_surfaces;
  if (const YAML::Node e =
          Effect(n, f, "dark_surfaces", {"reference_range", "reference_reflectivity", "softness"},
                 &d.enabled)) {
    const std::string ef = f + ".dark_surfaces";
    Get(e, ef, "reference_range", &d.reference_range);
    Get(e, ef, "reference_reflectivity", &d.reference_reflectivity);
    Get(e, ef, "softness", &d.softness);
  }
  GhostEffect& g = s->ghosts;
  if (const YAML::Node e =
          Effect(n, f, "ghosts", {"min_incidence_deg", "probability"}, &g.enabled)) {
    const std::string ef = f + ".ghosts";
    Get(e, ef, "min_incidence_deg", &g.min_incidence_deg);
    Get(e, ef, "probability", &g.probability);
  }
}

}  // namespace yaml_fields
}  // namespace sim
}  // namespace is_graphs
