#pragma once

#include <optional>
#include <string>
#include <utility>

namespace is_graphs {

/// Either a value or an error message (a C++17 stand-in for std::expected).
///
///   Result<AGraph> r = LoadAGraph(path);
///   if (!r.ok()) { std::cerr << r.error() << "\n"; return 1; }
///   const AGraph& graph = r.value();
template <typename T>
class Result {
 public:
  static Result Ok(T value) { return Result(std::move(value), std::string()); }
  static Result Error(std::string message) { return Result(std::nullopt, std::move(message)); }

  bool ok() const { return value_.has_value(); }
  explicit operator bool() const { return ok(); }

  /// Requires ok().
  const T& value() const& { return *value_; }
  T& value() & { return *value_; }
  T&& value() && { return std::move(*value_); }

  /// Empty when ok().
  const std::string& error() const { return error_; }

 private:
  Result(std::optional<T> value, std::string error)
      : value_(std::move(value)), error_(std::move(error)) {}

  std::optional<T> value_;
  std::string error_;
};

}  // namespace is_graphs
