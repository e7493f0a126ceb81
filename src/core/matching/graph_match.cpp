#include "is_graphs/matching/graph_match.h"

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

}  // namespace matching
}  // namespace is_graphs
