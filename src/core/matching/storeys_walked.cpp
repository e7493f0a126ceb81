#include "is_graphs/matching/storeys_walked.h"

#include <cmath>

namespace is_graphs {
namespace matching {

std::vector<int> StoreysFittingLevels(const std::map<int, double>& elevations,
                                      const std::map<int, double>& levels, int current,
                                      double tolerance, double per_metre) {
  const auto here = levels.find(current);
  if (here == levels.end() || levels.size() < 2) return {};
  std::map<int, int> fits;  // storey -> other levels with a storey where they should be
  int most = 0;
  for (const auto& [storey, elevation] : elevations) {
    int n = 0;
    for (const auto& [level, height] : levels) {
      if (level == current) continue;
      const double rise = height - here->second;
      const double bound = tolerance + per_metre * std::abs(rise);
      for (const auto& other : elevations) {
        if (other.first != storey && std::abs(other.second - (elevation + rise)) <= bound) {
          ++n;
          break;
        }
      }
    }
    fits[storey] = n;
    if (n > most) most = n;
  }
  std::vector<int> out;
  if (most == 0) return out;
  for (const auto& [storey, n] : fits)
    if (n == most) out.push_back(storey);
  return out;
}

std::optional<std::vector<int>> StoreysFromKnownLevels(const std::map<int, double>& elevations,
                                                       const std::map<int, double>& levels,
                                                       const std::map<int, int>& known, int current,
                                                       double tolerance, double per_metre) {
  const auto here = levels.find(current);
  if (here == levels.end()) return std::nullopt;
  std::vector<int> out;
  bool constrained = false;
  for (const auto& [storey, elevation] : elevations) {
    bool fits = true;
    for (const auto& [level, known_storey] : known) {
      const auto there = levels.find(level);
      const auto known_elevation = elevations.find(known_storey);
      if (level == current || there == levels.end() || known_elevation == elevations.end())
        continue;
      constrained = true;
      const double rise = here->second - there->second;  // from the known level to this one
      const double bound = tolerance + per_metre * std::abs(rise);
      if (std::abs(elevation - (known_elevation->second + rise)) > bound) fits = false;
    }
    if (fits) out.push_back(storey);
  }
  if (!constrained) return std::nullopt;
  return out;
}

}  // namespace matching
}  // namespace is_graphs
