#pragma once

// Internal helpers of the scenario YAML readers (scenario_yaml*.cpp): typed field access whose
// errors carry the field's YAML path. Not installed; not part of the API.

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "is_graphs/sim/scenario_config.h"

namespace is_graphs {
namespace sim {
namespace yaml_fields {

// Thrown by the scenario YAML readers only, caught in ParseScenarioYaml: a field path and what
// is wrong.
struct FieldError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

[[noreturn]] inline void Fail(const std::string& field, const std::string& what) {
  throw FieldError(field + ": " + what);
}

inline std::string Join(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

inline void CheckMap(const YAML::Node& node, const std::string& field,
                     const std::set<std::string>& allowed) {
  if (!node.IsMap()) Fail(field.empty() ? "(top level)" : field, "must be a mapping");
  for (const auto& kv : node) {
    const std::string key = kv.first.as<std::string>();
    if (!allowed.count(key)) {
      std::string list;
      for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
      Fail(Join(field, key), "unknown key (expected one of: " + list + ")");
    }
  }
}

template <typename T>
inline T As(const YAML::Node& node, const std::string& field, const char* expected) {
  try {
    return node.as<T>();
  } catch (const YAML::Exception&) {
    Fail(field, std::string("must be ") + expected);
  }
}

inline double Number(const YAML::Node& node, const std::string& field) {
  return As<double>(node, field, "a number");
}

// Reads map[key] into `out` when present.
inline void Get(const YAML::Node& map, const std::string& parent, const char* key, double* out) {
  if (map[key]) *out = Number(map[key], Join(parent, key));
}
inline void Get(const YAML::Node& map, const std::string& parent, const char* key,
                std::string* out) {
  if (map[key]) *out = As<std::string>(map[key], Join(parent, key), "a string");
}
inline void Get(const YAML::Node& map, const std::string& parent, const char* key, bool* out) {
  if (map[key]) *out = As<bool>(map[key], Join(parent, key), "true or false");
}
inline void Get(const YAML::Node& map, const std::string& parent, const char* key, int* out) {
  if (map[key]) *out = As<int>(map[key], Join(parent, key), "an integer");
}

inline std::vector<double> Numbers(const YAML::Node& node, const std::string& field,
                                   std::size_t min_n, std::size_t max_n) {
  if (!node.IsSequence() || node.size() < min_n || node.size() > max_n) {
    Fail(field, "must be a list of " + std::to_string(min_n) +
                    (min_n == max_n ? "" : " to " + std::to_string(max_n)) + " numbers");
  }
  std::vector<double> v;
  for (std::size_t i = 0; i < node.size(); ++i) {
    v.push_back(Number(node[i], field + "[" + std::to_string(i) + "]"));
  }
  return v;
}

inline Eigen::Vector2d Vec2(const YAML::Node& node, const std::string& field) {
  const std::vector<double> v = Numbers(node, field, 2, 2);
  return {v[0], v[1]};
}

inline Eigen::Vector3d Vec3(const YAML::Node& node, const std::string& field) {
  const std::vector<double> v = Numbers(node, field, 3, 3);
  return {v[0], v[1], v[2]};
}

inline std::vector<std::string> Strings(const YAML::Node& node, const std::string& field) {
  if (!node.IsSequence()) Fail(field, "must be a list of strings");
  std::vector<std::string> v;
  for (std::size_t i = 0; i < node.size(); ++i) {
    v.push_back(As<std::string>(node[i], field + "[" + std::to_string(i) + "]", "a string"));
  }
  return v;
}

/// The `scene` section.
void ParseScene(const YAML::Node& node, SceneConfig* scene);
/// The `sensor.effects` section.
void ParseSensorEffects(const YAML::Node& node, SensorEffectsConfig* effects);

}  // namespace yaml_fields
}  // namespace sim
}  // namespace is_graphs
