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

}  // namespace matching
}  // namespace is_graphs
