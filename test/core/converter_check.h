#pragma once

// Whether the IFC converter can run here: the tests that convert the project's buildings skip,
// saying why, where it cannot (a workspace of the user's own, built without the project's venv).

#include <string>

#include "is_graphs/agraph/ifc_conversion.h"
#include "is_graphs/common/run_process.h"

namespace is_graphs {
namespace testing {

/// "" when the converter's default interpreter (IS_GRAPHS_PYTHON, the project's venv after
/// `make setup`) imports what scripts/ifc_to_agraph.py needs; else why not. Checked once.
inline const std::string& IfcConverterMissing() {
  static const std::string why = [] {
    const agraph::IfcConversionConfig config;
    const ProcessOutput run =
        RunProcess({config.python, "-c", "import ifcopenshell, numpy, shapely"});
    if (run.started && run.exit_code == 0) return std::string();
    return "no IFC converter: " + config.python +
           " cannot import ifcopenshell, numpy and shapely (make setup makes the project's "
           ".venv with them; or configure with -DIS_GRAPHS_PYTHON=/path/to/python3)";
  }();
  return why;
}

}  // namespace testing
}  // namespace is_graphs
