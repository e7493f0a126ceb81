#pragma once
// Dijkstra on a small dense graph given by an edge-cost function: the route planner's room graph
// and PathInsideRoom's visibility graph. Internal to the simulator.

#include <algorithm>
#include <functional>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

namespace is_graphs {
namespace sim {

// Shortest path from `from` to `to` on n nodes, `cost(u, v)` infinite where there is no edge:
// the node indices after `from` up to `to`, empty when `to` is unreachable.
inline std::vector<int> Dijkstra(int n, int from, int to,
                                 const std::function<double(int, int)>& cost) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<double> dist(n, kInf);
  std::vector<int> prev(n, -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  dist[from] = 0.0;
  queue.push({0.0, from});
  while (!queue.empty()) {
    const auto [d, u] = queue.top();
    queue.pop();
    if (d > dist[u]) continue;
    for (int v = 0; v < n; ++v) {
      if (v == u) continue;
      const double c = cost(u, v);
      if (c < kInf && d + c < dist[v]) {
        dist[v] = d + c;
        prev[v] = u;
        queue.push({dist[v], v});
      }
    }
  }
  std::vector<int> path;
  if (dist[to] == kInf) return path;
  for (int v = to; v != from; v = prev[v]) path.push_back(v);
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace sim
}  // namespace is_graphs
