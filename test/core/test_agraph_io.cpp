#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <nlohmann/json.hpp>

#include "fixtures.h"
#include "is_graphs/agraph/agraph_io.h"

namespace is_graphs {
namespace agraph {
namespace {

using nlohmann::json;

bool Contains(const std::vector<int>& ids, int id) {
  return std::find(ids.begin(), ids.end(), id) != ids.end();
}

TEST(AGraphIo, LoadsTheTwoRoomsFixture) {
  const Result<AGraph> loaded = LoadAGraph(testing::TwoRoomsPath());
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  const AGraph& g = loaded.value();
  EXPECT_EQ(g.building, "Two Rooms");
  EXPECT_EQ(g.source.schema, "IFC4");
  ASSERT_EQ(g.storeys.size(), 1u);
  EXPECT_EQ(g.storeys[0].name, "Ground Floor");
  EXPECT_EQ(g.surfaces.size(), 10u);
  EXPECT_EQ(g.walls.size(), 5u);
  ASSERT_EQ(g.rooms.size(), 2u);
  ASSERT_EQ(g.doorways.size(), 2u);
  EXPECT_EQ(g.warnings.size(), 1u);
  EXPECT_EQ(g.mesh, testing::DataPath("two_rooms.obj"));  // resolved against the file's folder
  EXPECT_TRUE(std::filesystem::path(g.mesh).is_absolute());

  const WallSurface& s3 = g.surfaces[3];
  EXPECT_EQ(s3.ifc_id, 102);
  EXPECT_EQ(s3.orientation, geometry::Orientation::kX);
  EXPECT_DOUBLE_EQ(s3.plane.d, 8.2);
  EXPECT_EQ(g.surfaces[0].orientation, geometry::Orientation::kY);
  EXPECT_DOUBLE_EQ(g.surfaces[0].plane.d, 0.0);  // through the origin: the normal is kept
  EXPECT_DOUBLE_EQ(g.surfaces[0].plane.normal.y(), 1.0);
  EXPECT_EQ(g.rooms[1].long_name, "Office B");
  EXPECT_EQ(g.rooms[0].polygon.size(), 4u);
  EXPECT_TRUE(g.walls[0].external);
  EXPECT_FALSE(g.walls[4].external);
  EXPECT_EQ(g.doorways[1].rooms, std::vector<int>{1});
}

TEST(AGraphIo, RoomSurfaceRelations) {
  const AGraph g = LoadAGraph(testing::TwoRoomsPath()).value();
  for (const Room& room : g.rooms) {
    EXPECT_EQ(room.surfaces.size(), 4u);
    for (int s : room.surfaces) {
      const WallSurface& surface = g.surfaces[s];
      // Normals of a room's surfaces point into it; the surface lists the room back.
      EXPECT_GT(surface.plane.SignedDistance(room.center), 0.0) << "room " << room.id << " s " << s;
      EXPECT_TRUE(Contains(surface.rooms, room.id));
      EXPECT_TRUE(Contains(room.walls, surface.wall));
      // start/end follow the tangent t = ẑ × n.
      const Eigen::Vector2d along = surface.end - surface.start;
      EXPECT_GT(along.dot(surface.Tangent().head<2>()), 0.0);
    }
  }
  // Both rooms face the inner side of the south wall, only room 1 the east wall.
  EXPECT_EQ(g.surfaces[0].rooms, (std::vector<int>{0, 1}));
  EXPECT_EQ(g.surfaces[2].rooms, (std::vector<int>{1}));
}

TEST(AGraphIo, DoorwayRoomRelations) {
  const AGraph g = LoadAGraph(testing::TwoRoomsPath()).value();
  for (const Doorway& d : g.doorways) {
    for (int r : d.rooms) EXPECT_TRUE(Contains(g.rooms[r].doorways, d.id));
    // The doorway lies on its host wall's mid-plane: half the thickness from each face.
    const Wall& wall = g.walls[d.wall];
    EXPECT_NEAR(g.surfaces[wall.surface_a].plane.SignedDistance(d.position), -0.1, 1e-9);
    EXPECT_NEAR(g.surfaces[wall.surface_b].plane.SignedDistance(d.position), -0.1, 1e-9);
  }
  const Doorway& inner = g.doorways[0];
  EXPECT_EQ(inner.rooms, (std::vector<int>{0, 1}));
  EXPECT_LT(g.rooms[0].center.x(), inner.position.x());
  EXPECT_GT(g.rooms[1].center.x(), inner.position.x());
}

TEST(AGraphIo, SaveLoadRoundTrip) {
  const AGraph g = LoadAGraph(testing::TwoRoomsPath()).value();
  const std::string dir = testing::ScratchDir("agraph_io_round_trip");
  const std::string path = dir + "/copy.agraph.json";
  ASSERT_EQ(SaveAGraph(g, path), "");
  const Result<AGraph> again = LoadAGraph(path);
  ASSERT_TRUE(again.ok()) << again.error();
  EXPECT_EQ(ToJsonText(again.value()), ToJsonText(g));  // mesh resolves to the same file
  EXPECT_EQ(again.value().mesh, g.mesh);
}

// A copy of the fixture, changed by `mutate`, must fail to load with all of `expected` in the
// message.
struct BrokenCase {
  const char* name;
  std::function<void(json&)> mutate;
  std::vector<std::string> expected;
};

TEST(AGraphIo, ValidationErrorsNameTheElement) {
  const json fixture = json::parse(testing::ReadFile(testing::TwoRoomsPath()));
  const std::string dir = testing::ScratchDir("agraph_io_errors");
  const std::vector<BrokenCase> cases = {
      {"format", [](json& j) { j["format"] = "other"; }, {"format is \"other\""}},
      {"newer_version", [](json& j) { j["version"] = 2; }, {"version 2 is newer", "update"}},
      {"id_not_index",
       [](json& j) { j["wall_surfaces"][3]["id"] = 5; },
       {"wall_surfaces[3] (IfcWall #102)", "id 5 differs from its index 3"}},
      {"non_unit_normal",
       [](json& j) {
         j["wall_surfaces"][3]["normal"] = {0.5, 0.0, 0.0};
       },
       {"wall_surfaces[3] (IfcWall #102): normal is not a unit vector"}},
      {"surface_wall",
       [](json& j) { j["wall_surfaces"][0]["wall"] = 9; },
       {"wall_surfaces[0] (IfcWall #101)", "walls id 9"}},
      {"surface_room",
       [](json& j) {
         j["wall_surfaces"][2]["rooms"] = {1, 7};
       },
       {"wall_surfaces[2]", "rooms id 7"}},
      {"wall_surface_range",
       [](json& j) {
         j["walls"][1]["surfaces"] = {2, 42};
       },
       {"walls[1] (IfcWall #102)", "wall_surfaces id 42"}},
      {"wall_one_surface",
       [](json& j) { j["walls"][1]["surfaces"] = {2}; },
       {"walls[1] (IfcWall #102)", "two wall_surfaces ids"}},
      {"wall_back_reference",
       [](json& j) {
         j["walls"][4]["surfaces"] = {8, 3};
       },
       {"walls[4] (IfcWall #105)", "do not refer back"}},
      {"surface_back_reference",
       [](json& j) { j["wall_surfaces"][9]["wall"] = 3; },
       {"walls[4] (IfcWall #105)", "do not refer back"}},
      {"room_surface",
       [](json& j) { j["rooms"][1]["surfaces"].push_back(10); },
       {"rooms[1] (IfcSpace #202)", "wall_surfaces id 10"}},
      {"room_wall",
       [](json& j) { j["rooms"][0]["walls"].push_back(-1); },
       {"rooms[0] (IfcSpace #201)", "walls id -1"}},
      {"room_doorway",
       [](json& j) { j["rooms"][0]["doorways"] = {2}; },
       {"rooms[0] (IfcSpace #201)", "doorways id 2"}},
      {"room_storey",
       [](json& j) { j["rooms"][0]["storey"] = 3; },
       {"rooms[0] (IfcSpace #201)", "storeys id 3"}},
      {"polygon",
       [](json& j) {
         j["rooms"][0]["polygon"] = {{0, 0}, {1, 0}};
       },
       {"rooms[0] (IfcSpace #201)", "polygon has 2 vertices"}},
      {"doorway_three_rooms",
       [](json& j) {
         j["doorways"][0]["rooms"] = {0, 1, 1};
       },
       {"doorways[0] (IfcDoor #301)", "one or two"}},
      {"doorway_no_room",
       [](json& j) { j["doorways"][1]["rooms"] = json::array(); },
       {"doorways[1] (IfcDoor #302)", "one or two"}},
      {"doorway_room_range",
       [](json& j) { j["doorways"][1]["rooms"] = {5}; },
       {"doorways[1] (IfcDoor #302)", "rooms id 5"}},
      {"doorway_same_room",
       [](json& j) {
         j["doorways"][0]["rooms"] = {1, 1};
       },
       {"doorways[0] (IfcDoor #301)", "twice"}},
      {"doorway_wall",
       [](json& j) { j["doorways"][0]["wall"] = 5; },
       {"doorways[0] (IfcDoor #301)", "walls id 5"}},
      {"missing_field",
       [](json& j) { j["walls"][2].erase("center"); },
       {"walls[2] (IfcWall #103)", "missing field 'center'"}},
      {"wrong_type",
       [](json& j) { j["rooms"][0]["name"] = 5; },
       {"rooms[0] (IfcSpace #201)", "'name' must be a string"}},
      {"orientation",
       [](json& j) { j["wall_surfaces"][4]["orientation"] = "z"; },
       {"wall_surfaces[4] (IfcWall #103)", "orientation"}},
      {"missing_array", [](json& j) { j.erase("doorways"); }, {"missing field 'doorways'"}},
      {"no_ifc_id",
       [](json& j) {
         j["walls"][1]["ifc_id"] = -1;
         j["walls"][1]["surfaces"] = {2};
       },
       {"walls[1]: surfaces"}},
  };
  for (const BrokenCase& c : cases) {
    SCOPED_TRACE(c.name);
    json broken = fixture;
    c.mutate(broken);
    const std::string path = dir + "/" + c.name + ".agraph.json";
    testing::WriteFile(path, broken.dump(2));
    const Result<AGraph> loaded = LoadAGraph(path);
    ASSERT_FALSE(loaded.ok());
    EXPECT_EQ(loaded.error().rfind(path + ": ", 0), 0u) << loaded.error();  // names the file
    for (const std::string& part : c.expected) {
      EXPECT_NE(loaded.error().find(part), std::string::npos)
          << "expected \"" << part << "\" in: " << loaded.error();
    }
  }
}

TEST(AGraphIo, NearlyUnitNormalIsRenormalized) {
  json j = json::parse(testing::ReadFile(testing::TwoRoomsPath()));
  j["wall_surfaces"][3]["normal"] = {1.0005, 0.0, 0.0};
  j["wall_surfaces"][3]["d"] = 8.2041;  // scaled like the normal: the same plane x = 8.2
  const std::string path = testing::ScratchDir("agraph_io_renormalize") + "/n.agraph.json";
  testing::WriteFile(path, j.dump());
  const Result<AGraph> loaded = LoadAGraph(path);
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  EXPECT_NEAR(loaded.value().surfaces[3].plane.normal.norm(), 1.0, 1e-15);
  EXPECT_NEAR(loaded.value().surfaces[3].plane.d, 8.2, 1e-12);
}

TEST(AGraphIo, MissingOrientationIsClassified) {
  json j = json::parse(testing::ReadFile(testing::TwoRoomsPath()));
  j["wall_surfaces"][2].erase("orientation");
  const Result<AGraph> loaded = ParseAGraph(j.dump(), "inline.agraph.json");
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  EXPECT_EQ(loaded.value().surfaces[2].orientation, geometry::Orientation::kX);
}

// Converter 2 types its doorways (door / opening / virtual) and reports what it dropped; a
// version-1 file (no kind) holds doors; an unknown kind is an error naming the doorway.
TEST(AGraphIo, DoorwayKindsAndTheReport) {
  json j = json::parse(testing::ReadFile(testing::TwoRoomsPath()));
  ASSERT_GE(j["doorways"].size(), 2u);
  j["doorways"][0]["kind"] = "virtual";
  j["doorways"][1]["kind"] = "opening";
  j["report"] = json::array({{{"storey", 0},
                              {"name", "Ground Floor"},
                              {"dropped",
                               {{{"ifc_class", "IfcVirtualElement"},
                                 {"reason", "joins spaces on different storeys"},
                                 {"count", 2}}}}}});
  const Result<AGraph> loaded = ParseAGraph(j.dump(), "kinds.agraph.json");
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  const AGraph& g = loaded.value();
  EXPECT_EQ(g.doorways[0].kind, DoorwayKind::kVirtual);
  EXPECT_FALSE(g.doorways[0].InWall());
  EXPECT_EQ(g.doorways[1].kind, DoorwayKind::kOpening);
  EXPECT_TRUE(g.doorways[1].InWall());
  ASSERT_EQ(g.dropped.size(), 1u);
  EXPECT_EQ(g.dropped[0].ifc_class, "IfcVirtualElement");
  EXPECT_EQ(g.dropped[0].count, 2);
  // Through the writer and back: the same kinds and report.
  const Result<AGraph> again = ParseAGraph(ToJsonText(g), "again.agraph.json");
  ASSERT_TRUE(again.ok()) << again.error();
  EXPECT_EQ(again.value().doorways[0].kind, DoorwayKind::kVirtual);
  EXPECT_EQ(again.value().doorways[1].kind, DoorwayKind::kOpening);
  ASSERT_EQ(again.value().dropped.size(), 1u);
  EXPECT_EQ(again.value().dropped[0].reason, "joins spaces on different storeys");

  json v1 = json::parse(testing::ReadFile(testing::TwoRoomsPath()));
  for (auto& d : v1["doorways"]) d.erase("kind");
  const Result<AGraph> old = ParseAGraph(v1.dump(), "v1.agraph.json");
  ASSERT_TRUE(old.ok()) << old.error();
  for (const auto& d : old.value().doorways) EXPECT_EQ(d.kind, DoorwayKind::kDoor);

  j["doorways"][1]["kind"] = "portal";
  const Result<AGraph> bad = ParseAGraph(j.dump(), "bad_kind.agraph.json");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().find("doorways[1]"), std::string::npos) << bad.error();
  EXPECT_NE(bad.error().find("'portal'"), std::string::npos) << bad.error();
}

TEST(AGraphIo, TextErrors) {
  const std::string dir = testing::ScratchDir("agraph_io_text");
  const Result<AGraph> missing = LoadAGraph(dir + "/absent.agraph.json");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().find("absent.agraph.json: no such A-Graph file"), std::string::npos);

  const Result<AGraph> garbage = ParseAGraph("{\"format\": ", "bad.agraph.json");
  ASSERT_FALSE(garbage.ok());
  EXPECT_NE(garbage.error().find("bad.agraph.json: not valid JSON"), std::string::npos);

  std::string text = testing::ReadFile(testing::TwoRoomsPath());
  const std::string first_d = "\"d\": 0.0";
  ASSERT_NE(text.find(first_d), std::string::npos);
  text.replace(text.find(first_d), first_d.size(), "\"d\": 1e999");
  const Result<AGraph> infinite = ParseAGraph(text, "inf.agraph.json");
  ASSERT_FALSE(infinite.ok());
  EXPECT_NE(infinite.error().find("inf.agraph.json: not valid JSON"), std::string::npos)
      << infinite.error();
  EXPECT_NE(infinite.error().find("1e999"), std::string::npos) << infinite.error();
}

}  // namespace
}  // namespace agraph
}  // namespace is_graphs
