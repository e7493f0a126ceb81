#include <gtest/gtest.h>

#include <cmath>

#include "fixtures.h"
#include "is_graphs/agraph/agraph_io.h"
#include "is_graphs/agraph/agraph_queries.h"
#include "is_graphs/agraph/agraph_validation.h"

namespace is_graphs {
namespace agraph {
namespace {

// The fixture with a copy of its storey 3 m higher: storey 1 "First Floor".
AGraph TwoStoreys() {
  AGraph g = LoadAGraph(testing::TwoRoomsPath()).value();
  const int n_s = static_cast<int>(g.surfaces.size()), n_w = static_cast<int>(g.walls.size());
  const int n_r = static_cast<int>(g.rooms.size()), n_d = static_cast<int>(g.doorways.size());
  const auto shift = [](std::vector<int> ids, int offset) {
    for (int& id : ids) id += offset;
    return ids;
  };
  g.storeys.push_back(g.storeys[0]);
  g.storeys[1].id = 1;
  g.storeys[1].name = "First Floor";
  g.storeys[1].elevation = 3.0;
  for (int i = 0; i < n_s; ++i) {
    WallSurface s = g.surfaces[i];
    s.id += n_s;
    s.storey = 1;
    s.wall += n_w;
    s.rooms = shift(s.rooms, n_r);
    g.surfaces.push_back(s);
  }
  for (int i = 0; i < n_w; ++i) {
    Wall w = g.walls[i];
    w.id += n_w;
    w.storey = 1;
    w.surface_a += n_s;
    w.surface_b += n_s;
    w.center.z() += 3.0;
    g.walls.push_back(w);
  }
  for (int i = 0; i < n_r; ++i) {
    Room r = g.rooms[i];
    r.id += n_r;
    r.storey = 1;
    r.name = "1" + r.name;
    r.surfaces = shift(r.surfaces, n_s);
    r.walls = shift(r.walls, n_w);
    r.doorways = shift(r.doorways, n_d);
    r.center.z() += 3.0;
    g.rooms.push_back(r);
  }
  for (int i = 0; i < n_d; ++i) {
    Doorway d = g.doorways[i];
    d.id += n_d;
    d.storey = 1;
    d.wall += n_w;
    d.rooms = shift(d.rooms, n_r);
    g.doorways.push_back(d);
  }
  EXPECT_EQ(ValidateAGraph(g), "");
  return g;
}

TEST(AGraphQueries, Tangent) {
  WallSurface s;
  s.plane = geometry::Plane(Eigen::Vector3d::UnitX(), 1.0);
  EXPECT_LT((s.Tangent() - Eigen::Vector3d::UnitY()).norm(), 1e-12);  // ẑ × x̂ = ŷ
  s.plane = geometry::Plane(Eigen::Vector3d(0.0, -2.0, 0.0), 1.0);
  EXPECT_LT((s.Tangent() - Eigen::Vector3d::UnitX()).norm(), 1e-12);  // ẑ × −ŷ = x̂
  const double a = M_PI / 6.0;
  s.plane = geometry::Plane(Eigen::Vector3d(std::cos(a), std::sin(a), 0.0), 0.0);
  EXPECT_LT((s.Tangent() - Eigen::Vector3d(-0.5, std::sqrt(3.0) / 2.0, 0.0)).norm(), 1e-12);
  s.start = Eigen::Vector2d(1.0, 1.0);
  s.end = Eigen::Vector2d(4.0, 5.0);
  EXPECT_DOUBLE_EQ(s.Length(), 5.0);
}

TEST(AGraphQueries, SelectStoreyByNameReindexes) {
  const AGraph g = TwoStoreys();
  const Result<AGraph> upper = SelectStorey(g, "First Floor");
  ASSERT_TRUE(upper.ok()) << upper.error();
  const AGraph& u = upper.value();
  EXPECT_EQ(ValidateAGraph(u), "");
  ASSERT_EQ(u.storeys.size(), 1u);
  EXPECT_EQ(u.storeys[0].id, 0);
  EXPECT_EQ(u.storeys[0].name, "First Floor");
  EXPECT_EQ(u.surfaces.size(), 10u);
  EXPECT_EQ(u.walls.size(), 5u);
  ASSERT_EQ(u.rooms.size(), 2u);
  ASSERT_EQ(u.doorways.size(), 2u);
  EXPECT_EQ(u.rooms[1].name, "12");
  EXPECT_DOUBLE_EQ(u.rooms[1].center.z(), 4.4);
  // References point into the sub-graph, as in the single-storey original.
  EXPECT_EQ(u.walls[4].surface_a, 8);
  EXPECT_EQ(u.walls[4].surface_b, 9);
  EXPECT_EQ(u.rooms[1].surfaces, (std::vector<int>{0, 2, 4, 9}));
  EXPECT_EQ(u.doorways[0].rooms, (std::vector<int>{0, 1}));
  EXPECT_EQ(u.doorways[1].wall, 0);
  for (size_t i = 0; i < u.surfaces.size(); ++i) EXPECT_EQ(u.surfaces[i].id, static_cast<int>(i));
}

TEST(AGraphQueries, SelectStoreyByIndex) {
  const AGraph g = TwoStoreys();
  const Result<AGraph> lower = SelectStorey(g, "0");
  ASSERT_TRUE(lower.ok()) << lower.error();
  EXPECT_EQ(lower.value().storeys[0].name, "Ground Floor");
  EXPECT_EQ(ToJsonText(lower.value()),
            ToJsonText(LoadAGraph(testing::TwoRoomsPath()).value()));  // the original again
  ASSERT_TRUE(SelectStorey(g, 1).ok());
  EXPECT_EQ(SelectStorey(g, 1).value().storeys[0].name, "First Floor");
}

TEST(AGraphQueries, SelectUnknownStorey) {
  const AGraph g = TwoStoreys();
  for (const std::string& name : std::vector<std::string>{"Roof", "2", "-1", ""}) {
    const Result<AGraph> none = SelectStorey(g, name);
    ASSERT_FALSE(none.ok()) << name;
    EXPECT_NE(none.error().find("unknown storey \"" + name + "\""), std::string::npos);
    EXPECT_NE(none.error().find("0 \"Ground Floor\", 1 \"First Floor\""), std::string::npos)
        << none.error();
  }
  EXPECT_FALSE(SelectStorey(g, 5).ok());
}

TEST(AGraphQueries, DoorwayWithoutRoomsOnTheStoreyIsDropped) {
  AGraph g = TwoStoreys();
  g.doorways[3].rooms = {1};  // storey-1 door to a storey-0 room
  g.rooms[3].doorways = {2};
  const AGraph u = SelectStorey(g, 1).value();
  EXPECT_EQ(u.doorways.size(), 1u);
  EXPECT_EQ(u.rooms[1].doorways, (std::vector<int>{0}));
  EXPECT_EQ(u.warnings.size(), g.warnings.size() + 1);
  EXPECT_EQ(ValidateAGraph(u), "");
}

TEST(AGraphQueries, SignedArea) {
  const AGraph g = LoadAGraph(testing::TwoRoomsPath()).value();
  EXPECT_NEAR(SignedArea(g.rooms[0].polygon), 15.6, 1e-12);  // counter-clockwise: positive
  std::vector<Eigen::Vector2d> clockwise(g.rooms[0].polygon.rbegin(), g.rooms[0].polygon.rend());
  EXPECT_NEAR(SignedArea(clockwise), -15.6, 1e-12);
}

TEST(AGraphQueries, Summarize) {
  const std::string summary = Summarize(TwoStoreys());
  for (const char* expected :
       {"building: Two Rooms", "storeys:  2", "storey 0 \"Ground Floor\"",
        "storey 1 \"First Floor\"", "wall surfaces: 10 (x 6, y 4, other 0)", "walls:         5",
        "doorways:      2 (2 doors, 0 openings, 0 virtual; 1 to outdoors)", "rooms:         2",
        "\"Office A\"  15.60 m^2", "warnings: 1"}) {
    EXPECT_NE(summary.find(expected), std::string::npos) << "no \"" << expected << "\" in\n"
                                                         << summary;
  }
}

// The file's length unit by name: a millimetre file printed "unit 0.00 m" (issue 24).
TEST(AGraphQueries, SummarizeNamesTheLengthUnit) {
  AGraph g = TwoStoreys();
  const std::pair<double, const char*> units[] = {{1.0, "unit metre\n"},
                                                  {0.001, "unit millimetre (0.001 m)\n"},
                                                  {0.3048, "unit foot (0.3048 m)\n"},
                                                  {0.5, "unit 0.5 m\n"}};
  for (const auto& [metres, expected] : units) {
    g.source.length_unit_m = metres;
    const std::string summary = Summarize(g);
    EXPECT_NE(summary.find(expected), std::string::npos) << "no \"" << expected << "\" in\n"
                                                         << summary;
  }
}

}  // namespace
}  // namespace agraph
}  // namespace is_graphs
