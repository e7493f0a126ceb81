#include "json_fields.h"

#include <cmath>
#include <limits>

namespace is_graphs {
namespace agraph {
namespace internal {

using nlohmann::json;

JsonFields::JsonFields(const json& object, std::string label)
    : object_(object), label_(std::move(label)) {
  if (!object_.is_object()) Fail("is not a JSON object");
}

void JsonFields::Fail(const std::string& detail) const {
  throw FormatError(label_ + ": " + detail);
}

const json& JsonFields::Required(const char* key) const {
  const auto it = object_.find(key);
  if (it == object_.end()) Fail(std::string("missing field '") + key + "'");
  return *it;
}

double JsonFields::ToNumber(const json& value, const std::string& what) const {
  if (!value.is_number()) Fail(what + " must be a number, got " + value.dump());
  const double number = value.get<double>();
  if (!std::isfinite(number)) Fail(what + " is not finite");
  return number;
}

double JsonFields::Number(const char* key) const {
  return ToNumber(Required(key), std::string("'") + key + "'");
}

double JsonFields::NumberOr(const char* key, double fallback) const {
  return Has(key) ? Number(key) : fallback;
}

long JsonFields::Integer(const char* key) const {
  const json& value = Required(key);
  if (!value.is_number_integer()) {
    Fail(std::string("'") + key + "' must be an integer, got " + value.dump());
  }
  return value.get<long>();
}

long JsonFields::IntegerOr(const char* key, long fallback) const {
  return Has(key) ? Integer(key) : fallback;
}

std::string JsonFields::String(const char* key) const {
  const json& value = Required(key);
  if (!value.is_string()) Fail(std::string("'") + key + "' must be a string, got " + value.dump());
  return value.get<std::string>();
}

std::string JsonFields::StringOr(const char* key, const std::string& fallback) const {
  if (!Has(key) || object_.at(key).is_null()) return fallback;
  return String(key);
}

bool JsonFields::BoolOr(const char* key, bool fallback) const {
  if (!Has(key)) return fallback;
  const json& value = object_.at(key);
  if (!value.is_boolean()) Fail(std::string("'") + key + "' must be true or false");
  return value.get<bool>();
}

const json& JsonFields::Array(const char* key) const {
  const json& value = Required(key);
  if (!value.is_array()) Fail(std::string("'") + key + "' must be an array");
  return value;
}

Eigen::Vector2d JsonFields::Vector2(const char* key) const {
  const json& value = Array(key);
  if (value.size() != 2) Fail(std::string("'") + key + "' must have 2 numbers");
  return Eigen::Vector2d(ToNumber(value[0], std::string("'") + key + "'[0]"),
                         ToNumber(value[1], std::string("'") + key + "'[1]"));
}

Eigen::Vector3d JsonFields::Vector3(const char* key) const {
  const json& value = Array(key);
  if (value.size() != 3) Fail(std::string("'") + key + "' must have 3 numbers");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    v[i] = ToNumber(value[i], std::string("'") + key + "'[" + std::to_string(i) + "]");
  }
  return v;
}

std::vector<Eigen::Vector2d> JsonFields::Points2(const char* key) const {
  std::vector<Eigen::Vector2d> points;
  const json& value = Array(key);
  for (size_t i = 0; i < value.size(); ++i) {
    const std::string what = std::string("'") + key + "'[" + std::to_string(i) + "]";
    if (!value[i].is_array() || value[i].size() != 2) Fail(what + " must be [x, y]");
    points.emplace_back(ToNumber(value[i][0], what), ToNumber(value[i][1], what));
  }
  return points;
}

std::vector<int> JsonFields::Indices(const char* key) const {
  std::vector<int> indices;
  for (const json& value : Array(key)) {
    if (!value.is_number_integer()) {
      Fail(std::string("'") + key + "' must hold integer ids, got " + value.dump());
    }
    const long index = value.get<long>();
    if (index < std::numeric_limits<int>::min() || index > std::numeric_limits<int>::max()) {
      Fail(std::string("'") + key + "' holds an out-of-range id " + std::to_string(index));
    }
    indices.push_back(static_cast<int>(index));
  }
  return indices;
}

std::vector<int> JsonFields::IndicesOr(const char* key) const {
  return Has(key) ? Indices(key) : std::vector<int>();
}

std::vector<std::string> JsonFields::StringsOr(const char* key) const {
  std::vector<std::string> strings;
  if (!Has(key)) return strings;
  for (const json& value : Array(key)) {
    if (!value.is_string()) Fail(std::string("'") + key + "' must hold strings");
    strings.push_back(value.get<std::string>());
  }
  return strings;
}

}  // namespace internal
}  // namespace agraph
}  // namespace is_graphs
