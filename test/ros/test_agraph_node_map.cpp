// rostest of agraph_node's navigation side (docs/navigation.md): the latched `bim_map` of the
// office, `bim_map/as_built` after a `deviations` message, the `locate` service, bad parameters.
#include <gtest/gtest.h>
#include <is_graphs/AGraph.h>
#include <is_graphs/GraphMatch.h>
#include <is_graphs/Locate.h>
#include <is_graphs/WallDeviations.h>
#include <nav_msgs/OccupancyGrid.h>
#include <ros/ros.h>

#include <chrono>
#include <mutex>

#include "../../src/ros/agraph_conversions.h"
#include "is_graphs/navigation/occupancy_grid.h"
#include "is_graphs/navigation/places.h"
#include "node_runner.h"

namespace is_graphs {
namespace {

const std::string kOfficeIfc = std::string(IS_GRAPHS_SOURCE_DIR) + "/bim/office.ifc";

template <typename M>
boost::shared_ptr<const M> Wait(const std::string& topic, double seconds) {
  ros::NodeHandle nh;
  return ros::topic::waitForMessage<M>(topic, nh, ros::Duration(seconds));
}

std::int8_t CellAt(const nav_msgs::OccupancyGrid& map, const Eigen::Vector2d& p) {
  const int ix =
      static_cast<int>(std::floor((p.x() - map.info.origin.position.x) / map.info.resolution));
  const int iy =
      static_cast<int>(std::floor((p.y() - map.info.origin.position.y) / map.info.resolution));
  if (ix < 0 || iy < 0 || ix >= static_cast<int>(map.info.width) ||
      iy >= static_cast<int>(map.info.height))
    return -1;
  return map.data[static_cast<size_t>(iy) * map.info.width + ix];
}

const agraph::Wall& WallNamed(const agraph::AGraph& g, const std::string& name) {
  for (const auto& w : g.walls)
    if (w.name == name) return w;
  throw std::runtime_error("no wall " + name);
}

Eigen::Vector2d Middle(const agraph::AGraph& g, const agraph::Wall& w) {
  Eigen::Vector2d m = Eigen::Vector2d::Zero();
  for (const auto& p : navigation::WallFootprint(g, w)) m += 0.25 * p;
  return m;
}

TEST(AGraphNodeMap, PublishesTheStoreysMapLatched) {
  const auto graph_msg = Wait<is_graphs::AGraph>("a_graph", 180.0);
  ASSERT_TRUE(graph_msg);
  const auto map = Wait<nav_msgs::OccupancyGrid>("bim_map", 10.0);
  ASSERT_TRUE(map) << "no bim_map";
  const agraph::AGraph g = ros_conversions::FromMsg(*graph_msg);
  EXPECT_EQ(map->header.frame_id, "bim");
  EXPECT_FLOAT_EQ(map->info.resolution, 0.05f);
  ASSERT_EQ(map->data.size(), size_t(map->info.width) * map->info.height);
  // A wall occupied, the rooms' deepest points free, the margin unknown.
  EXPECT_EQ(CellAt(*map, Middle(g, WallNamed(g, "p_n3"))), 100);
  for (const auto& r : g.rooms)
    EXPECT_EQ(CellAt(*map, navigation::FarthestFromEdges(r.polygon, 0.01)), 0) << r.name;
  EXPECT_EQ(map->data.front(), -1);
  EXPECT_EQ(map->data.back(), -1);
}

TEST(AGraphNodeMap, AsBuiltFollowsTheDeviationsTopic) {
  const auto graph_msg = Wait<is_graphs::AGraph>("a_graph", 180.0);
  ASSERT_TRUE(graph_msg);
  const agraph::AGraph g = ros_conversions::FromMsg(*graph_msg);
  const agraph::Wall& n3 = WallNamed(g, "p_n3");
  const Eigen::Vector2d mid = Middle(g, n3);
  const auto planned = Wait<nav_msgs::OccupancyGrid>("bim_map/as_built", 10.0);
  ASSERT_TRUE(planned);
  EXPECT_EQ(CellAt(*planned, mid), 100) << "as built before any deviations: the plan";

  ros::NodeHandle nh;
  nav_msgs::OccupancyGrid::ConstPtr latest;
  std::mutex mutex;
  ros::Subscriber sub = nh.subscribe<nav_msgs::OccupancyGrid>(
      "bim_map/as_built", 1, [&](const nav_msgs::OccupancyGrid::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        latest = m;
      });
  ros::Publisher pub = nh.advertise<is_graphs::WallDeviations>("deviations", 1, true);
  is_graphs::WallDeviations deviations;
  deviations.header.frame_id = "bim";
  deviations.a_graph_sha256 = graph_msg->source_sha256;
  is_graphs::WallDeviation w;
  w.wall_id = n3.id;
  w.guid = n3.guid;
  w.status = is_graphs::WallDeviation::NOT_BUILT;
  const auto foot = navigation::WallFootprint(g, n3);
  w.start.x = 0.5 * (foot[0].x() + foot[3].x()), w.start.y = 0.5 * (foot[0].y() + foot[3].y());
  w.end.x = 0.5 * (foot[1].x() + foot[2].x()), w.end.y = 0.5 * (foot[1].y() + foot[2].y());
  deviations.walls.push_back(w);
  pub.publish(deviations);
  bool freed = false;
  for (int i = 0; i < 100 && !freed; ++i) {
    ros::Duration(0.1).sleep();
    std::lock_guard<std::mutex> lock(mutex);
    freed = latest && CellAt(*latest, mid) == 0;
  }
  EXPECT_TRUE(freed) << "p_n3 NOT_BUILT: still occupied in bim_map/as_built";
  const auto map = Wait<nav_msgs::OccupancyGrid>("bim_map", 5.0);
  ASSERT_TRUE(map);
  EXPECT_EQ(CellAt(*map, mid), 100) << "bim_map is the plan: deviations leave it";
}

TEST(AGraphNodeMap, LocateRoomsDoorsAndBadNames) {
  ASSERT_TRUE(Wait<is_graphs::AGraph>("a_graph", 180.0));
  ASSERT_TRUE(ros::service::waitForService("locate", ros::Duration(10.0)));
  ros::NodeHandle nh;
  ros::ServiceClient client = nh.serviceClient<is_graphs::Locate>("locate", /*persistent=*/true);
  is_graphs::Locate call;
  call.request.name = "Meeting room";
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_TRUE(client.call(call));
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_TRUE(call.response.success) << call.response.message;
  EXPECT_EQ(call.response.pose.header.frame_id, "bim");
  EXPECT_EQ(call.response.kind, "room");
  EXPECT_EQ(call.response.storey_name, "Ground floor");
  EXPECT_TRUE(call.response.free) << "the room's goal on a free cell of bim_map";
  EXPECT_EQ(call.response.match_free.size(), call.response.matches.size());
  EXPECT_LT(ms, 50.0) << "a locate round trip";
  std::printf("[ locate   ] round trip %.2f ms\n", ms);
  const auto graph_msg = Wait<is_graphs::AGraph>("a_graph", 5.0);
  const agraph::AGraph g = ros_conversions::FromMsg(*graph_msg);
  for (const auto& r : g.rooms) {
    if (r.name != "Meeting") continue;
    const Eigen::Vector2d goal(call.response.pose.pose.position.x,
                               call.response.pose.pose.position.y);
    EXPECT_GT(navigation::SignedDistanceToPolygon(r.polygon, goal), 0.5);
  }

  is_graphs::Locate door;
  door.request.name = g.doorways.at(0).guid;
  ASSERT_TRUE(client.call(door));
  EXPECT_TRUE(door.response.success) << door.response.message;
  EXPECT_EQ(door.response.kind, "door");
  EXPECT_TRUE(door.response.free) << door.response.message;

  is_graphs::Locate unknown;
  unknown.request.name = "Meetng";
  ASSERT_TRUE(client.call(unknown));
  EXPECT_FALSE(unknown.response.success);
  EXPECT_TRUE(unknown.response.matches.empty());
  EXPECT_NE(unknown.response.message.find("'Meeting'"), std::string::npos)
      << unknown.response.message;

  is_graphs::Locate storey;
  storey.request.name = "101";
  storey.request.storey = "Roof";
  ASSERT_TRUE(client.call(storey));
  EXPECT_FALSE(storey.response.success);
  EXPECT_NE(storey.response.message.find("Ground floor"), std::string::npos)
      << storey.response.message;
}

TEST(AGraphNodeMap, FollowsTheStoreyOfAUniqueMatchOnThisAGraph) {
  const auto graph = Wait<is_graphs::AGraph>("tower/a_graph", 180.0);
  ASSERT_TRUE(graph);
  ASSERT_EQ(graph->storeys.size(), 3u);
  ros::NodeHandle nh;
  nav_msgs::OccupancyGrid::ConstPtr latest;
  std::mutex mutex;
  ros::Subscriber sub = nh.subscribe<nav_msgs::OccupancyGrid>(
      "tower/bim_map", 1, [&](const nav_msgs::OccupancyGrid::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        latest = m;
      });
  const auto elevation = [&] {
    std::lock_guard<std::mutex> lock(mutex);
    return latest ? latest->info.origin.position.z : -1e9;
  };
  for (int i = 0; i < 100 && elevation() == -1e9; ++i) ros::Duration(0.1).sleep();
  EXPECT_DOUBLE_EQ(elevation(), graph->storeys[0].elevation) << "first: the lowest storey";

  ros::Publisher pub = nh.advertise<is_graphs::GraphMatch>("tower/graph_match", 1, true);
  is_graphs::GraphMatch match;
  match.status = is_graphs::GraphMatch::UNIQUE;
  match.storey_id = 2;
  match.a_graph_sha256 = "another building";
  pub.publish(match);
  ros::Duration(1.5).sleep();
  EXPECT_DOUBLE_EQ(elevation(), graph->storeys[0].elevation) << "a match on another A-Graph";
  match.a_graph_sha256 = graph->source_sha256;
  match.status = is_graphs::GraphMatch::AMBIGUOUS;
  pub.publish(match);
  ros::Duration(1.5).sleep();
  EXPECT_DOUBLE_EQ(elevation(), graph->storeys[0].elevation) << "an ambiguous match";
  match.status = is_graphs::GraphMatch::UNIQUE;
  pub.publish(match);
  for (int i = 0; i < 100 && elevation() != graph->storeys[2].elevation; ++i)
    ros::Duration(0.1).sleep();
  EXPECT_DOUBLE_EQ(elevation(), graph->storeys[2].elevation) << "the matched storey";
  EXPECT_GT(graph->storeys[2].elevation, graph->storeys[0].elevation);
}

std::pair<int, std::string> RunAgraphNode(const std::string& args) {
  return testing_support::RunNode(IS_GRAPHS_AGRAPH_NODE, "bad_map_agraph_node", args);
}

TEST(AGraphNodeMapBadInput, BadResolutionIsNamed) {
  const auto [code, out] = RunAgraphNode("_bim_file:=" + kOfficeIfc + " _map_resolution:=-0.05");
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("map_resolution"), std::string::npos) << out;
}

TEST(AGraphNodeMapBadInput, UnknownMapStoreyIsNamed) {
  ros::NodeHandle nh;
  std::string cache;
  nh.getParam("test_cache_dir", cache);
  const auto [code, out] = RunAgraphNode("_bim_file:=" + kOfficeIfc + " _cache_dir:=" + cache +
                                         " _map_storey:=Penthouse");
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("map_storey"), std::string::npos) << out;
  EXPECT_NE(out.find("Ground floor"), std::string::npos) << out;
}

}  // namespace
}  // namespace is_graphs
