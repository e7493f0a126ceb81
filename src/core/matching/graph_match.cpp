#include "is_graphs/matching/graph_match.h"

#include <algorithm>

namespace is_graphs {
namespace matching {

const char* ToString(MatchStatus status) {
  switch (status) {
    case MatchStatus::kNone:
      return "NONE";
    case MatchStatus::kAmbiguous:
      return "AMBIGUOUS";
    case MatchStatus::kUnique:
      return "UNIQUE";
  }
  return "?";
}

std::vector<int> CompetingStoreys(const GraphMatch& match) {
  std::vector<int> out;
  for (const auto& a : match.alternatives)
    if (a.storey >= 0 && a.storey != match.storey) out.push_back(a.storey);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace matching
}  // namespace is_graphs
