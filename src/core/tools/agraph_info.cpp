// agraph_info BIM_FILE [--storey NAME] [--cache-dir DIR]
//
// Loads a BIM (an .ifc, converted on the fly, or an .agraph.json), optionally keeps one storey,
// prints the A-Graph's summary, then builds and solves its Ceres problem and prints the solve
// summary. Exit code 1 with the error on stderr for bad input.

#include <iostream>
#include <string>

#include "is_graphs/agraph/agraph_problem.h"
#include "is_graphs/agraph/agraph_queries.h"
#include "is_graphs/agraph/ifc_conversion.h"

namespace {

constexpr char kUsage[] =
    "usage: agraph_info BIM_FILE [--storey NAME] [--cache-dir DIR]\n"
    "  BIM_FILE      an .ifc file (converted with scripts/ifc_to_agraph.py) or an .agraph.json\n"
    "  --storey NAME keep one storey, by name or index\n"
    "  --cache-dir D where converted IFC files are cached\n";

int Fail(const std::string& message) {
  std::cerr << "agraph_info: " << message << "\n";
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace is_graphs::agraph;
  std::string bim_file, storey;
  bool select_storey = false;
  IfcConversionConfig conversion;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-h" || arg == "--help") {
      std::cout << kUsage;
      return 0;
    }
    if (arg == "--storey" || arg == "--cache-dir") {
      if (i + 1 >= argc) return Fail(arg + " needs a value\n" + kUsage);
      (arg == "--storey" ? storey : conversion.cache_dir) = argv[++i];
      select_storey = select_storey || arg == "--storey";
    } else if (!arg.empty() && arg[0] == '-') {
      return Fail("unknown option " + arg + "\n" + kUsage);
    } else if (bim_file.empty()) {
      bim_file = arg;
    } else {
      return Fail("more than one BIM_FILE given\n" + std::string(kUsage));
    }
  }
  if (bim_file.empty()) return Fail(std::string("no BIM_FILE given\n") + kUsage);

  is_graphs::Result<AGraph> graph = LoadBim(bim_file, conversion);
  if (!graph.ok()) return Fail(graph.error());
  if (select_storey) {
    graph = SelectStorey(graph.value(), storey);
    if (!graph.ok()) return Fail(bim_file + ": " + graph.error());
  }
  std::cout << Summarize(graph.value());

  const AGraphProblemConfig config;
  const std::string invalid = config.Validate();
  if (!invalid.empty()) return Fail(invalid);
  AGraphProblem problem(graph.value(), config);
  const AGraphSolveSummary summary = problem.Solve();
  std::cout << "A-Graph problem: " << summary.parameter_blocks << " parameter blocks, "
            << summary.residual_blocks << " residual blocks\n"
            << "  initial cost " << summary.initial_cost << ", final cost " << summary.final_cost
            << ", " << summary.iterations << " iterations, " << summary.time_s << " s ("
            << summary.termination << ")\n";
  if (!summary.usable) return Fail("the A-Graph problem's solution is not usable");
  return 0;
}
