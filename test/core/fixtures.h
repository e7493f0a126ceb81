#pragma once
// Test helpers: paths of the fixtures and of a per-test scratch folder.

#include <filesystem>
#include <fstream>
#include <string>

namespace is_graphs {
namespace testing {

inline std::string DataPath(const std::string& name) {
  return std::string(IS_GRAPHS_SOURCE_DIR) + "/test/data/" + name;
}

inline std::string TwoRoomsPath() { return DataPath("two_rooms.agraph.json"); }

/// A fresh, empty folder IS_GRAPHS_TEST_TMP_DIR/<name>.
inline std::string ScratchDir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(IS_GRAPHS_TEST_TMP_DIR) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

inline void WriteFile(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
}

inline std::string ReadFile(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
}

}  // namespace testing
}  // namespace is_graphs
