#pragma once
// Internal to the core: typed, checked access to the fields of one JSON object, throwing a
// FormatError whose message names the element and the field.

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace is_graphs {
namespace agraph {
namespace internal {

struct FormatError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class JsonFields {
 public:
  /// `label` names the object in errors ("wall_surfaces[3] (IfcWall #1234)").
  JsonFields(const nlohmann::json& object, std::string label);

  const std::string& label() const { return label_; }
  bool Has(const char* key) const { return object_.contains(key); }

  double Number(const char* key) const;
  double NumberOr(const char* key, double fallback) const;
  long Integer(const char* key) const;
  long IntegerOr(const char* key, long fallback) const;
  std::string String(const char* key) const;
  std::string StringOr(const char* key, const std::string& fallback) const;
  bool BoolOr(const char* key, bool fallback) const;
  Eigen::Vector2d Vector2(const char* key) const;
  Eigen::Vector3d Vector3(const char* key) const;
  std::vector<Eigen::Vector2d> Points2(const char* key) const;
  std::vector<int> Indices(const char* key) const;
  std::vector<int> IndicesOr(const char* key) const;  // [] when absent
  std::vector<std::string> StringsOr(const char* key) const;
  const nlohmann::json& Array(const char* key) const;

  [[noreturn]] void Fail(const std::string& detail) const;

 private:
  const nlohmann::json& Required(const char* key) const;
  double ToNumber(const nlohmann::json& value, const std::string& what) const;

  const nlohmann::json& object_;
  std::string label_;
};

}  // namespace internal
}  // namespace agraph
}  // namespace is_graphs
