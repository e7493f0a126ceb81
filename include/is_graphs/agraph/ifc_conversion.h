#pragma once

#include <string>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/common/result.h"

// Set by CMake for is_graphs_core and its users: the project's venv Python and the converter.
#ifndef IS_GRAPHS_DEFAULT_PYTHON
#define IS_GRAPHS_DEFAULT_PYTHON "python3"
#endif
#ifndef IS_GRAPHS_DEFAULT_CONVERTER
#define IS_GRAPHS_DEFAULT_CONVERTER "scripts/ifc_to_agraph.py"
#endif

namespace is_graphs {
namespace agraph {

struct IfcConversionConfig {
  std::string python{IS_GRAPHS_DEFAULT_PYTHON};        // interpreter with IfcOpenShell
  std::string converter{IS_GRAPHS_DEFAULT_CONVERTER};  // scripts/ifc_to_agraph.py
  std::string cache_dir;  // where converted files are cached; "" = DefaultCacheDir()

  /// "" when valid, else what is wrong, naming the parameter.
  std::string Validate() const;
};

/// $ROS_HOME/is_graphs/cache, else $HOME/.ros/is_graphs/cache, else /tmp/is_graphs/cache (as
/// agraph_node and scripts/demo.sh use).
std::string DefaultCacheDir();

/// Runs `python converter IFC --cache-dir DIR --quiet` (no shell involved) and returns the
/// path of the .agraph.json it wrote (the last line it prints). On failure the error carries
/// the exit code and the converter's stderr (whose lines name the file and the IFC entity),
/// or says which of python, converter or IFC file is missing.
Result<std::string> ConvertIfc(const IfcConversionConfig& config, const std::string& ifc_path);

/// Loads a BIM file by its extension (case-insensitive): ".ifc" is converted (ConvertIfc) and
/// its A-Graph loaded; ".json" (an .agraph.json) is loaded; anything else is an error naming
/// the extension.
Result<AGraph> LoadBim(const std::string& path, const IfcConversionConfig& config = {});

}  // namespace agraph
}  // namespace is_graphs
