#pragma once

#include <string>

#include "is_graphs/common/result.h"
#include "is_graphs/sim/scenario_config.h"

namespace is_graphs {
namespace sim {

/// Reads a scenario YAML (bags/*.yaml; the format is documented in bags/README.md) and validates
/// it. `base_dir` anchors a relative `building` path (the repository root). Errors name the file,
/// the line and the field: "bags/d3.yaml:12: trajectory.speed: must be in [0.3, 1.2] m/s, got
/// -1". Unknown
/// keys are errors (they are almost always typos).
Result<ScenarioConfig> LoadScenarioYaml(const std::string& path, const std::string& base_dir);

/// As LoadScenarioYaml, from YAML text; `name` prefixes errors.
Result<ScenarioConfig> ParseScenarioYaml(const std::string& text, const std::string& name,
                                         const std::string& base_dir);

/// "name:LINE: error" for an error that starts with a field path ("scene.glass.max_layers: ...",
/// "scene.outside[2].position ..."), LINE the 1-based line of that field in the YAML `text` (or
/// of its nearest parent there); "name: error" when the text does not parse or names no field.
std::string WithYamlLine(const std::string& text, const std::string& name,
                         const std::string& error);

}  // namespace sim
}  // namespace is_graphs
