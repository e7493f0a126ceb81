// bim_map BIM_FILE [--storey NAME] [-o DIR] [--resolution M] [--slice-min M] [--slice-max M]
//         [--margin M] [--cache-dir DIR]
//
// The BIM as a navigation map (docs/navigation.md): per storey (all, or the one named), the
// occupancy grid agraph_node publishes on `bim_map`, written as map_server's YAML + PGM
// (DIR/<file stem>_<storey>.yaml, .pgm) for move_base's or nav2's map_server. Prints one line
// per map written. Exit code 1 with the error on stderr for bad input.

#include <filesystem>
#include <iostream>
#include <string>

#include "is_graphs/agraph/agraph_queries.h"
#include "is_graphs/agraph/ifc_conversion.h"
#include "is_graphs/navigation/map_files.h"

namespace {

constexpr char kUsage[] =
    "usage: bim_map BIM_FILE [--storey NAME] [-o DIR] [--resolution M] [--slice-min M]\n"
    "               [--slice-max M] [--margin M] [--cache-dir DIR]\n"
    "  BIM_FILE        an .ifc file (converted with scripts/ifc_to_agraph.py) or an .agraph.json\n"
    "  --storey NAME   one storey, by name or index (default: every storey)\n"
    "  -o DIR          where the maps are written (default: .)\n"
    "  --resolution M  m per cell (0.05); --slice-min/--slice-max M: the robot's height band\n"
    "                  above the floor whose sections are occupied (0.1, 1.0); --margin M (1.0)\n";

int Fail(const std::string& message) {
  std::cerr << "bim_map: " << message << "\n";
  return 1;
}

std::string FileSafe(std::string s) {
  for (auto& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  return s.empty() ? "storey" : s;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace is_graphs;
  std::string bim_file, storey, out_dir = ".";
  agraph::IfcConversionConfig conversion;
  navigation::GridConfig config;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-h" || arg == "--help") {
      std::cout << kUsage;
      return 0;
    }
    if (arg == "--storey" || arg == "-o" || arg == "--cache-dir" || arg == "--resolution" ||
        arg == "--slice-min" || arg == "--slice-max" || arg == "--margin") {
      if (i + 1 >= argc) return Fail(arg + " needs a value\n" + kUsage);
      const std::string value = argv[++i];
      try {
        if (arg == "--storey")
          storey = value;
        else if (arg == "-o")
          out_dir = value;
        else if (arg == "--cache-dir")
          conversion.cache_dir = value;
        else if (arg == "--resolution")
          config.resolution = std::stod(value);
        else if (arg == "--slice-min")
          config.slice_min = std::stod(value);
        else if (arg == "--slice-max")
          config.slice_max = std::stod(value);
        else
          config.margin = std::stod(value);
      } catch (const std::exception&) {
        return Fail(arg + ": not a number: '" + value + "'");
      }
    } else if (!arg.empty() && arg[0] == '-') {
      return Fail("unknown option " + arg + "\n" + kUsage);
    } else if (bim_file.empty()) {
      bim_file = arg;
    } else {
      return Fail("more than one BIM_FILE given\n" + std::string(kUsage));
    }
  }
  if (bim_file.empty()) return Fail(std::string("no BIM_FILE given\n") + kUsage);
  if (const std::string bad = config.Validate(); !bad.empty()) return Fail("--" + bad);

  const Result<agraph::AGraph> graph = agraph::LoadBim(bim_file, conversion);
  if (!graph.ok()) return Fail(graph.error());
  std::vector<int> storeys;
  if (!storey.empty()) {
    const auto found = agraph::FindStorey(graph.value(), storey);
    if (!found.ok()) return Fail(bim_file + ": --storey: " + found.error());
    storeys.push_back(found.value());
  } else {
    for (size_t s = 0; s < graph.value().storeys.size(); ++s) storeys.push_back(s);
  }
  Result<geometry::TriangleMesh> mesh = Result<geometry::TriangleMesh>::Error("no mesh");
  if (!graph.value().mesh.empty()) mesh = geometry::LoadObj(graph.value().mesh);
  if (!mesh.ok()) std::cerr << "bim_map: " << mesh.error() << ": walls from the A-Graph only\n";

  const std::string stem = std::filesystem::path(bim_file).stem().string();
  for (int s : storeys) {
    const auto one = agraph::SelectStorey(graph.value(), s);
    if (!one.ok()) return Fail(one.error());
    const auto grid =
        navigation::BuildStoreyGrid(one.value(), mesh.ok() ? &mesh.value() : nullptr, config);
    if (!grid.ok() && !storey.empty()) return Fail(bim_file + ": " + grid.error());
    if (!grid.ok()) {  // every storey: one without rooms or walls (a roof, a site) is skipped
      std::cerr << "bim_map: " << bim_file << ": " << grid.error() << "\n";
      continue;
    }
    const std::string yaml =
        (std::filesystem::path(out_dir) /
         (FileSafe(stem) + "_" + FileSafe(graph.value().storeys[s].name) + ".yaml"))
            .string();
    if (const std::string bad = navigation::WriteMapFiles(grid.value(), yaml); !bad.empty())
      return Fail(bad);
    const Eigen::Vector3i counts = navigation::CountCells(grid.value());
    std::cout << yaml << ": storey '" << graph.value().storeys[s].name << "', "
              << grid.value().width << " x " << grid.value().height << " cells of "
              << config.resolution << " m, origin (" << grid.value().origin.x() << ", "
              << grid.value().origin.y() << "), " << counts[0] << " free, " << counts[1]
              << " occupied, " << counts[2] << " unknown\n";
  }
  return 0;
}
