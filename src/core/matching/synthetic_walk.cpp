#include "is_graphs/matching/synthetic_walk.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>

#include "is_graphs/matching/wall_crossings.h"

namespace is_graphs {
namespace matching {
namespace {

using Chain = std::vector<Eigen::Vector2d>;

constexpr double kDoorMargin = 0.4;       // m, as the matcher's default
constexpr double kMinSharedLength = 1.0;  // m of a wall two rooms share to walk through it

// Appends the points after chain.back() up to b, `spacing` apart at most.
void Densify(Chain& chain, const Eigen::Vector2d& b, double spacing) {
  const Eigen::Vector2d a = chain.back();
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / spacing)));
  for (int i = 1; i <= n; ++i) chain.push_back(a + (b - a) * (static_cast<double>(i) / n));
}

// Where rooms a and b share a wall by at least kMinSharedLength away from its doorways: the
// middle of the shared part (pushed to `out`).
void SharedWallPoints(const agraph::AGraph& g, int a, int b, std::vector<Eigen::Vector2d>& out) {
  for (int sa : g.rooms[a].surfaces)
    for (int sb : g.rooms[b].surfaces) {
      const auto& A = g.surfaces[sa];
      const auto& B = g.surfaces[sb];
      if (sa == sb || A.wall < 0 || A.wall != B.wall || A.Length() < kMinSharedLength) continue;
      const Eigen::Vector2d t = (A.end - A.start) / A.Length();
      const double u1 = (B.start - A.start).dot(t), u2 = (B.end - A.start).dot(t);
      const double lo = std::max(0.0, std::min(u1, u2)),
                   hi = std::min(A.Length(), std::max(u1, u2));
      if (hi - lo < kMinSharedLength) continue;
      const Eigen::Vector2d mid = A.start + t * (0.5 * (lo + hi));
      const bool at_door = std::any_of(g.doorways.begin(), g.doorways.end(), [&](const auto& d) {
        return d.wall == A.wall &&
               (d.position.template head<2>() - mid).norm() < 0.5 * d.width + 2.0 * kDoorMargin;
      });
      if (!at_door) out.push_back(mid);
    }
}

}  // namespace

std::vector<std::vector<Eigen::Vector2d>> SyntheticWalk(const agraph::AGraph& g,
                                                        const std::vector<int>& rooms,
                                                        double spacing, int through_walls,
                                                        std::mt19937_64& rng) {
  const int n = static_cast<int>(g.rooms.size());
  std::vector<int> taken;
  for (int r : rooms)
    if (r >= 0 && r < n && std::find(taken.begin(), taken.end(), r) == taken.end())
      taken.push_back(r);

  // Each room entered through a doorway it shares with a room entered before: a tree.
  std::map<int, std::vector<std::pair<int, int>>> children;  // room -> (room, doorway)
  std::vector<int> roots;
  for (size_t k = 0; k < taken.size(); ++k) {
    bool attached = false;
    for (size_t p = 0; p < k && !attached; ++p)
      for (int d : g.rooms[taken[k]].doorways) {
        if (d < 0 || d >= static_cast<int>(g.doorways.size())) continue;
        const auto& joins = g.doorways[d].rooms;
        if (std::find(joins.begin(), joins.end(), taken[p]) != joins.end()) {
          children[taken[p]].emplace_back(taken[k], d);
          attached = true;
          break;
        }
      }
    if (!attached) roots.push_back(taken[k]);
  }

  const WallCrossings walls(g, kDoorMargin);
  std::vector<Chain> chains;
  Chain current;
  auto flush = [&] {
    if (current.size() > 1) chains.push_back(current);
    current.clear();
  };
  auto go = [&](const Eigen::Vector2d& p, int storey) {
    if (!current.empty() && walls.Count({{current.back(), p}}, Pose2{}, storey) > 0) flush();
    if (current.empty())
      current.push_back(p);
    else
      Densify(current, p, spacing);
  };
  std::function<void(int)> visit = [&](int r) {
    const int storey = g.rooms[r].storey;
    const Eigen::Vector2d centre = g.rooms[r].center.head<2>();
    go(centre, storey);
    for (const auto& [child, door] : children[r]) {
      const Eigen::Vector2d at = g.doorways[door].position.head<2>();
      go(at, storey);
      visit(child);
      go(at, storey);
      go(centre, storey);
    }
  };
  for (int root : roots) {
    flush();
    visit(root);
  }
  flush();

  // Openings the plan does not have: from a room's centre through a wall into a neighbour's.
  std::vector<std::pair<std::pair<int, int>, Eigen::Vector2d>> openings;
  for (size_t i = 0; i < taken.size(); ++i)
    for (size_t j = 0; j < taken.size(); ++j) {
      if (i == j || g.rooms[taken[i]].storey != g.rooms[taken[j]].storey) continue;
      std::vector<Eigen::Vector2d> points;
      SharedWallPoints(g, taken[i], taken[j], points);
      for (const auto& p : points) openings.push_back({{taken[i], taken[j]}, p});
    }
  for (int k = 0; k < through_walls && !openings.empty(); ++k) {
    const auto& [pair, at] =
        openings[std::uniform_int_distribution<size_t>(0, openings.size() - 1)(rng)];
    Chain chain{g.rooms[pair.first].center.head<2>()};
    Densify(chain, at, spacing);
    Densify(chain, g.rooms[pair.second].center.head<2>(), spacing);
    chains.push_back(chain);
  }
  return chains;
}

}  // namespace matching
}  // namespace is_graphs
