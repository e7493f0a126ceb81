#pragma once
// The buildings the navigation tests run on: the project's (bim/*.ifc) and every IFC of
// ../shared/bim that converts, each with its mesh when the conversion wrote one.

#include <filesystem>
#include <map>
#include <memory>

#include "is_graphs/geometry/triangle_mesh.h"
#include "matching_test_helpers.h"

namespace is_graphs {
namespace testing {

struct NavBuilding {
  std::string name;
  const agraph::AGraph* graph;
  const geometry::TriangleMesh* mesh;  // nullptr when there is none
  bool project;                        // bim/ (else ../shared/bim)
};

inline std::vector<NavBuilding> NavigationBuildings() {
  static std::map<std::string, std::unique_ptr<geometry::TriangleMesh>> meshes;
  std::vector<std::filesystem::path> files;
  for (const std::string& dir :
       {std::string(IS_GRAPHS_SOURCE_DIR) + "/bim", std::string(IS_GRAPHS_SHARED_BIM_DIR)}) {
    if (!std::filesystem::exists(dir)) continue;
    std::vector<std::filesystem::path> here;
    for (const auto& e : std::filesystem::directory_iterator(dir))
      if (e.path().extension() == ".ifc") here.push_back(e.path());
    std::sort(here.begin(), here.end());
    files.insert(files.end(), here.begin(), here.end());
  }
  std::vector<NavBuilding> out;
  for (const auto& f : files) {
    std::string why;
    const agraph::AGraph* g = LoadBuildingOnce(f.string(), &why);
    if (!g) continue;
    auto& mesh = meshes[f.string()];
    if (!mesh && !g->mesh.empty()) {
      auto loaded = geometry::LoadObj(g->mesh);
      if (loaded.ok()) mesh = std::make_unique<geometry::TriangleMesh>(std::move(loaded).value());
    }
    const bool project = f.parent_path() == std::filesystem::path(IS_GRAPHS_SOURCE_DIR) / "bim";
    out.push_back({f.filename().string(), g, mesh.get(), project});
  }
  return out;
}

}  // namespace testing
}  // namespace is_graphs
