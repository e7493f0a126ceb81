#include "is_graphs/agraph/agraph_io.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "agraph_json.h"
#include "is_graphs/agraph/agraph_validation.h"
#include "json_fields.h"

namespace is_graphs {
namespace agraph {

namespace fs = std::filesystem;

Result<AGraph> ParseAGraph(const std::string& json_text, const std::string& path) {
  nlohmann::json root;
  try {
    root = nlohmann::json::parse(json_text);
  } catch (const nlohmann::json::exception& e) {  // parse_error, number overflow
    return Result<AGraph>::Error(path + ": not valid JSON: " + e.what());
  }
  AGraph graph;
  try {
    internal::AGraphFromJson(root, &graph);
  } catch (const internal::FormatError& e) {
    return Result<AGraph>::Error(path + ": " + e.what());
  }
  const std::string invalid = ValidateAGraph(graph);
  if (!invalid.empty()) return Result<AGraph>::Error(path + ": " + invalid);

  if (!graph.mesh.empty() && fs::path(graph.mesh).is_relative()) {
    const fs::path folder = fs::path(path).parent_path();
    std::error_code ec;
    const fs::path absolute = fs::absolute(folder / graph.mesh, ec);
    graph.mesh = (ec ? folder / graph.mesh : absolute).lexically_normal().string();
  }
  return Result<AGraph>::Ok(std::move(graph));
}

Result<AGraph> LoadAGraph(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    return Result<AGraph>::Error(path + ": no such A-Graph file");
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) return Result<AGraph>::Error(path + ": cannot be opened for reading");
  std::ostringstream text;
  text << file.rdbuf();
  return ParseAGraph(text.str(), path);
}

std::string ToJsonText(const AGraph& graph) { return internal::AGraphToJson(graph).dump(2) + "\n"; }

std::string SaveAGraph(const AGraph& graph, const std::string& path) {
  std::string mesh = graph.mesh;
  if (!mesh.empty() && fs::path(mesh).is_absolute()) {
    std::error_code ec;
    const fs::path folder = fs::absolute(fs::path(path), ec).parent_path();
    const fs::path relative = fs::path(mesh).lexically_relative(folder);
    if (!ec && !relative.empty()) mesh = relative.string();
  }
  nlohmann::json root = internal::AGraphToJson(graph);
  root["mesh"] = mesh;
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file) return path + ": cannot be opened for writing";
  file << root.dump(2) << "\n";
  file.close();
  if (!file) return path + ": write failed";
  return "";
}

}  // namespace agraph
}  // namespace is_graphs
