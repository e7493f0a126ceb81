#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "converter_check.h"
#include "fixtures.h"
#include "is_graphs/agraph/agraph_io.h"
#include "is_graphs/agraph/ifc_conversion.h"

namespace is_graphs {
namespace agraph {
namespace {

using nlohmann::json;

// Converter 7 gives each room the floor walked on (floor_z, floor_source): on a split-level
// storey a room may stand 0.45 m above or below the storey's elevation. The reader keeps them,
// the writer writes them back.
TEST(AGraphRoomFloors, FloorHeightsOfASplitLevelStoreyAreRead) {
  json j = json::parse(testing::ReadFile(testing::TwoRoomsPath()));
  j["storeys"][0]["elevation"] = -0.6;
  j["rooms"][0]["floor_z"] = 0.0;
  j["rooms"][0]["floor_source"] = "slab";
  j["rooms"][1]["floor_z"] = -0.45;
  j["rooms"][1]["floor_source"] = "space";
  const Result<AGraph> loaded = ParseAGraph(j.dump(), "split.agraph.json");
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  const AGraph& g = loaded.value();
  EXPECT_DOUBLE_EQ(g.rooms[0].floor_z, 0.0);
  EXPECT_EQ(g.rooms[0].floor_source, "slab");
  EXPECT_DOUBLE_EQ(g.rooms[1].floor_z, -0.45);
  EXPECT_EQ(g.rooms[1].floor_source, "space");

  const Result<AGraph> again = ParseAGraph(ToJsonText(g), "again.agraph.json");
  ASSERT_TRUE(again.ok()) << again.error();
  EXPECT_DOUBLE_EQ(again.value().rooms[1].floor_z, -0.45);
  EXPECT_EQ(again.value().rooms[1].floor_source, "space");
}

// A file of converter 6 or older has no floor_z: each room stands on its storey's elevation,
// and floor_source is "" (not from the file).
TEST(AGraphRoomFloors, OlderFilesFallBackToTheStoreyElevation) {
  json j = json::parse(testing::ReadFile(testing::TwoRoomsPath()));
  ASSERT_FALSE(j["rooms"][0].contains("floor_z"));
  j["storeys"][0]["elevation"] = 0.25;
  const Result<AGraph> loaded = ParseAGraph(j.dump(), "old.agraph.json");
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  for (const Room& r : loaded.value().rooms) {
    EXPECT_DOUBLE_EQ(r.floor_z, 0.25) << r.name;
    EXPECT_EQ(r.floor_source, "") << r.name;
  }
}

TEST(AGraphRoomFloors, ANonNumericFloorIsAnErrorNamingTheRoom) {
  json j = json::parse(testing::ReadFile(testing::TwoRoomsPath()));
  j["rooms"][1]["floor_z"] = "low";
  const Result<AGraph> bad = ParseAGraph(j.dump(), "bad.agraph.json");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().find("rooms[1]"), std::string::npos) << bad.error();
  EXPECT_NE(bad.error().find("floor_z"), std::string::npos) << bad.error();
}

// The real converter on make_building's split-level fixture: Upper at the storey's level, Lower
// 0.45 m down, joined by door d_step (three risers): each room's floor from its slab, the door
// between both.
TEST(AGraphRoomFloors, RealConverterOnTheSplitLevelFixture) {
  const std::string ifc = testing::DataPath("split_two_rooms.ifc");
  IfcConversionConfig config;
  if (!std::filesystem::exists(ifc)) GTEST_SKIP() << ifc << " is not there";
  if (!std::filesystem::exists(config.converter)) GTEST_SKIP() << "no " << config.converter;
  if (config.python.find('/') != std::string::npos && access(config.python.c_str(), X_OK) != 0) {
    GTEST_SKIP() << "no Python at " << config.python << " (make setup creates the venv)";
  }
  if (!testing::IfcConverterMissing().empty()) GTEST_SKIP() << testing::IfcConverterMissing();
  config.cache_dir = testing::ScratchDir("agraph_room_floors_real") + "/cache";
  const Result<AGraph> loaded = LoadBim(ifc, config);
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  const AGraph& g = loaded.value();
  ASSERT_EQ(g.rooms.size(), 2u);
  for (const Room& r : g.rooms) {
    EXPECT_NEAR(r.floor_z, r.name == "Lower" ? -0.45 : 0.0, 1e-6) << r.name;
    EXPECT_EQ(r.floor_source, "slab") << r.name;
  }
  int joining = 0;
  for (const Doorway& d : g.doorways) joining += d.rooms.size() == 2 ? 1 : 0;
  EXPECT_EQ(joining, 1);
}

}  // namespace
}  // namespace agraph
}  // namespace is_graphs
