// An S-plane along several collinear A-surfaces (a wall the converter split in two, a corridor
// wall split by doorways) is paired with each of them, and the merge weighs them as one plane.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "fixtures.h"
#include "is_graphs/agraph/agraph_io.h"
#include "is_graphs/agraph/agraph_validation.h"
#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/graph_matcher.h"
#include "is_graphs/matching/room_descriptor.h"
#include "is_graphs/matching/synthetic_sgraph.h"
#include "is_graphs/merging/merger.h"
#include "matching_test_helpers.h"

namespace is_graphs {
namespace {

/// `g` with the wall of `face` cut in two at `fraction` of the face's length, as a converter
/// that splits walls at junctions writes it: both faces halved, the far halves a new wall, every
/// room bounded by a face bounded by its pieces. Returns the new piece of `face`.
int SplitFace(agraph::AGraph& g, int face, double fraction) {
  const int new_wall = static_cast<int>(g.walls.size());
  agraph::Wall wall = g.walls[g.surfaces[face].wall];
  const bool first = wall.surface_a == face;
  wall.id = new_wall;
  for (int* side : {&wall.surface_a, &wall.surface_b}) {
    agraph::WallSurface piece = g.surfaces[*side];
    const Eigen::Vector2d cut = piece.start + fraction * (piece.end - piece.start);
    g.surfaces[*side].end = cut;
    piece.start = cut;
    piece.id = static_cast<int>(g.surfaces.size());
    piece.wall = new_wall;
    for (int r : piece.rooms) {
      g.rooms[r].surfaces.push_back(piece.id);
      g.rooms[r].walls.push_back(new_wall);
    }
    *side = piece.id;
    g.surfaces.push_back(piece);
  }
  g.walls.push_back(wall);
  g.source.sha256 += "-split";
  return first ? wall.surface_a : wall.surface_b;
}

/// The longest face of `g` bounding at least one room.
int LongestRoomFace(const agraph::AGraph& g) {
  int best = -1;
  for (const auto& s : g.surfaces)
    if (!s.rooms.empty() && (best < 0 || s.Length() > g.surfaces[best].Length())) best = s.id;
  return best;
}

TEST(CollinearSurfaces, ARoomKeepsEveryPieceOfASplitFace) {
  agraph::AGraph g = agraph::LoadAGraph(testing::TwoRoomsPath()).value();
  const int face = LongestRoomFace(g);
  const int piece = SplitFace(g, face, 0.3);
  ASSERT_EQ(agraph::ValidateAGraph(g), "");
  for (const auto& room : matching::DescribeARooms(g)) {
    const auto& a_room = g.rooms[room.id];
    if (std::find(a_room.surfaces.begin(), a_room.surfaces.end(), piece) == a_room.surfaces.end())
      continue;
    // The two pieces are one feature, and it names both.
    int holding = 0;
    for (const auto& f : room.planes) {
      const std::set<int> pieces(f.pieces.begin(), f.pieces.end());
      if (pieces.count(face) || pieces.count(piece)) {
        ++holding;
        EXPECT_EQ(pieces, (std::set<int>{face, piece})) << "room " << room.id;
      }
    }
    EXPECT_EQ(holding, 1) << "room " << room.id;
  }
}

TEST(CollinearSurfaces, AnSPlaneAlongASplitWallIsPairedWithBothPiecesAndMergedAsOne) {
  IS_GRAPHS_BUILDING_OR_SKIP(plan, testing::ProjectBim("office.ifc"));
  // The S-Graph is seen in the building as built (one face); the plan has it in two pieces.
  matching::SyntheticSGraphConfig c;
  c.bim_T_map = geometry::IsometryFromXYYaw(12.0, -4.0, 0.7);
  c.offset_noise = 0.01;
  c.seed = 5;
  const matching::SyntheticSGraph s = matching::MakeSyntheticSGraph(*plan, c);
  agraph::AGraph split = *plan;
  const int face = LongestRoomFace(split);
  const int piece = SplitFace(split, face, 0.5);
  ASSERT_EQ(agraph::ValidateAGraph(split), "");

  matching::GraphMatcher matcher;
  matcher.SetAGraph(split);
  const matching::GraphMatch m = matcher.Match(s.graph);
  ASSERT_EQ(m.status, matching::MatchStatus::kUnique);
  std::string why;
  ASSERT_TRUE(testing::MatchIsCorrect(m, s, &why)) << why;
  std::set<int> on_face;  // the S-planes seen along the split face
  for (const auto& [s_id, a_id] : s.plane_truth)
    if (a_id == face) on_face.insert(s_id);
  ASSERT_FALSE(on_face.empty()) << "the synthetic S-Graph did not see face " << face;
  int both = 0;
  for (int s_id : on_face) {
    std::set<int> paired;
    for (const auto& p : m.surface_pairs)
      if (p.s_id == s_id) paired.insert(p.a_id);
    both += paired.count(face) && paired.count(piece);
  }
  EXPECT_GT(both, 0) << "no S-plane along face " << face << " is paired with piece " << piece;

  // The merge: each piece weighs half, so B_x_M is what the unsplit plan gives, also when the
  // face was built 6 cm off the plan (pieces weighing as much as the face would pull twice).
  matching::GraphMatch m_whole = m;
  m_whole.a_graph_sha256 = plan->source.sha256;
  m_whole.surface_pairs.erase(
      std::remove_if(m_whole.surface_pairs.begin(), m_whole.surface_pairs.end(),
                     [&](const matching::MatchPair& p) { return p.a_id == piece; }),
      m_whole.surface_pairs.end());
  agraph::AGraph plan_moved = *plan, split_moved = split;
  for (agraph::WallSurface* f :
       {&plan_moved.surfaces[face], &split_moved.surfaces[face], &split_moved.surfaces[piece]}) {
    f->plane.d += 0.06;  // 6 cm behind the face
    f->start -= 0.06 * f->plane.normal.head<2>();
    f->end -= 0.06 * f->plane.normal.head<2>();
  }
  const std::pair<const agraph::AGraph*, const agraph::AGraph*> cases[] = {
      {plan, &split}, {&plan_moved, &split_moved}};
  // Without deviation states the split merge is the whole one; with them each piece is a wall
  // of its own under its own prior, so they may differ by a little of the 6 cm.
  for (const bool deviations : {false, true}) {
    merging::MergerConfig config;
    config.estimate_wall_deviations = deviations;
    const double tolerance = deviations ? 0.005 : 0.001;
    for (const auto& [whole_plan, split_plan] : cases) {
      merging::Merger whole{config}, pieces{config};
      ASSERT_EQ(whole.SetAGraph(*whole_plan), "");
      ASSERT_EQ(pieces.SetAGraph(*split_plan), "");
      const auto out_whole = whole.OnMatch(m_whole, s.graph);
      const auto out_pieces = pieces.OnMatch(m, s.graph);
      ASSERT_TRUE(out_whole.merged) << out_whole.message;
      ASSERT_TRUE(out_pieces.merged) << out_pieces.message;
      EXPECT_EQ(out_pieces.solution.surfaces.size(), out_whole.solution.surfaces.size() + 1);
      const Eigen::Vector3d a = geometry::ToXYYaw(out_whole.bim_T_map);
      const Eigen::Vector3d b = geometry::ToXYYaw(out_pieces.bim_T_map);
      const std::string what =
          std::string(whole_plan == plan ? "" : "moved ") + (deviations ? "with deviations" : "");
      EXPECT_LT((a.head<2>() - b.head<2>()).norm(), tolerance) << what;
      EXPECT_LT(std::abs(geometry::NormalizeAngle(a.z() - b.z())), 0.02 * M_PI / 180.0) << what;
      const Eigen::Vector3d truth = geometry::ToXYYaw(s.bim_T_map);
      EXPECT_LT((b.head<2>() - truth.head<2>()).norm(), 0.05) << what;
    }
  }
}

}  // namespace
}  // namespace is_graphs
