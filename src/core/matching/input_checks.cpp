#include "is_graphs/matching/input_checks.h"

#include <cmath>
#include <set>

namespace is_graphs {
namespace matching {
namespace {

bool Finite(const geometry::Plane& p) { return p.normal.allFinite() && std::isfinite(p.d); }

}  // namespace

std::vector<std::string> CheckAGraph(const agraph::AGraph& graph) {
  std::vector<std::string> out;
  if (graph.rooms.empty()) out.push_back("A-Graph: no rooms");
  for (size_t i = 0; i < graph.surfaces.size(); ++i) {
    const auto& s = graph.surfaces[i];
    if (s.id != static_cast<int>(i))
      out.push_back("A-Graph: wall-surface [" + std::to_string(i) + "] has id " +
                    std::to_string(s.id) + " (duplicate or not dense)");
    if (!Finite(s.plane))
      out.push_back("A-Graph: wall-surface " + std::to_string(s.id) + " has a non-finite plane");
  }
  for (size_t i = 0; i < graph.rooms.size(); ++i) {
    const auto& r = graph.rooms[i];
    const std::string name = "A-Graph: room " + std::to_string(r.id) + " '" + r.name + "'";
    if (r.id != static_cast<int>(i))
      out.push_back(name + " at [" + std::to_string(i) + "]: duplicate or not dense id");
    if (!r.center.allFinite()) out.push_back(name + ": non-finite centre");
    if (r.surfaces.empty()) out.push_back(name + ": no wall-surfaces");
    for (int sid : r.surfaces) {
      if (sid < 0 || sid >= static_cast<int>(graph.surfaces.size()))
        out.push_back(name + ": names wall-surface " + std::to_string(sid) +
                      " which does not exist");
    }
  }
  return out;
}

std::vector<std::string> CheckSGraph(const sgraph::SGraph& graph) {
  std::vector<std::string> out;
  const std::string rev = "S-Graph rev " + std::to_string(graph.revision);
  // Without rooms the wall planes still match (the corner proposals): only a graph with
  // neither has nothing to match.
  if (graph.rooms.empty() && graph.planes.empty())
    out.push_back(rev + ": no rooms and no planes: nothing to match");
  std::set<int> plane_ids;
  for (const auto& p : graph.planes) {
    if (!plane_ids.insert(p.id).second)
      out.push_back(rev + ": duplicate plane id " + std::to_string(p.id) + " (first one used)");
    if (!Finite(p.plane))
      out.push_back(rev + ": plane " + std::to_string(p.id) + " has a non-finite normal or d");
  }
  std::set<int> room_ids;
  for (const auto& r : graph.rooms) {
    const std::string name = rev + ": room " + std::to_string(r.id);
    if (!room_ids.insert(r.id).second) out.push_back(name + ": duplicate id (first one used)");
    if (!r.center.allFinite()) out.push_back(name + ": non-finite centre");
    if (r.planes.empty()) out.push_back(name + ": no planes");
    for (int pid : r.planes) {
      if (!plane_ids.count(pid))
        out.push_back(name + ": names plane " + std::to_string(pid) + " which does not exist");
    }
  }
  return out;
}

}  // namespace matching
}  // namespace is_graphs
