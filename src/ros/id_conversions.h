#pragma once

#include <algorithm>
#include <vector>

namespace is_graphs {
namespace ros_conversions {

/// Id lists between the core (int) and the messages (uint32).
template <typename Out, typename In>
std::vector<Out> CastIds(const std::vector<In>& ids) {
  std::vector<Out> out(ids.size());
  std::transform(ids.begin(), ids.end(), out.begin(), [](In id) { return static_cast<Out>(id); });
  return out;
}

}  // namespace ros_conversions
}  // namespace is_graphs
