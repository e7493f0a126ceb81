#pragma once
// Test helper: the hand-made storey of the deviation tests (test_wall_deviations,
// test_doorway_status): two rooms 4 x 4 m side by side, walls 0-3 the exterior (S, E, N, W;
// their inner faces, no thickness), wall 4 the partition at x = 4, 0.1 m thick (surfaces 4 at
// x = 4.05 facing +x and 5 at x = 3.95 facing -x). Walls named exterior0-3 and partition.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "matching_test_helpers.h"

namespace is_graphs {
namespace testing {

inline agraph::AGraph TwoRoomStorey() {
  agraph::AGraph g;
  const std::vector<std::array<Eigen::Vector2d, 3>> faces = {
      // start, end, normal (inward)
      {{{0, 0}, {8, 0}, {0, 1}}},       {{{8, 0}, {8, 4}, {-1, 0}}},
      {{{8, 4}, {0, 4}, {0, -1}}},      {{{0, 4}, {0, 0}, {1, 0}}},
      {{{4.05, 0}, {4.05, 4}, {1, 0}}}, {{{3.95, 4}, {3.95, 0}, {-1, 0}}}};
  for (size_t i = 0; i < faces.size(); ++i) {
    const int wall = std::min<int>(static_cast<int>(i), 4);
    auto s = MakeSurface(static_cast<int>(i), wall, 0, faces[i][0], faces[i][1], faces[i][2]);
    s.z_max = 3.0;
    g.surfaces.push_back(s);
  }
  for (int w = 0; w < 5; ++w) {
    agraph::Wall wall;
    wall.id = w;
    wall.name = w == 4 ? "partition" : "exterior" + std::to_string(w);
    wall.surface_a = w;
    wall.surface_b = w == 4 ? 5 : -1;
    wall.thickness = w == 4 ? 0.1 : 0.0;
    g.walls.push_back(wall);
  }
  return g;
}

}  // namespace testing
}  // namespace is_graphs
