#pragma once

// The simulation of a scenario YAML on the project's buildings, for the sim tests that need the
// IFC converter (skipped where it is missing).

#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <string>

#include "is_graphs/sim/scenario_yaml.h"
#include "is_graphs/sim/simulation.h"
#include "converter_check.h"

namespace is_graphs {
namespace sim {
namespace testing {

inline const std::string kSourceRoot = IS_GRAPHS_SOURCE_DIR;

/// Whether the office IFC and an IFC converter (IS_GRAPHS_PYTHON with IfcOpenShell) are there.
inline bool HaveConverter() {
  return std::ifstream(kSourceRoot + "/bim/office.ifc").good() &&
         is_graphs::testing::IfcConverterMissing().empty();
}

/// Parses `yaml` (paths relative to the source root) and prepares its simulation; nullptr and
/// a test failure on an error.
inline std::unique_ptr<Simulation> Prepare(const std::string& yaml) {
  const Result<ScenarioConfig> config = ParseScenarioYaml(yaml, "test.yaml", kSourceRoot);
  EXPECT_TRUE(config.ok()) << config.error();
  if (!config.ok()) return nullptr;
  auto sim = PrepareSimulation(config.value(), std::string(IS_GRAPHS_TEST_TMP_DIR) + "/bim_cache");
  EXPECT_TRUE(sim.ok()) << sim.error();
  return sim.ok() ? std::move(sim).value() : nullptr;
}

}  // namespace testing
}  // namespace sim
}  // namespace is_graphs
