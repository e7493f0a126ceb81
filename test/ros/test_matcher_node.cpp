// rostest of matcher_node (with agraph_node on bim/rotated.ifc): synthetic S-Graphs made from
// the published A-Graph with a known motion go out on `s_graph`; `graph_match` must be UNIQUE
// with the right pairs and motion, AMBIGUOUS for a lone rectangular room, never UNIQUE for
// malformed input (and the node keeps running); a bad parameter stops the node, named.
#include <gtest/gtest.h>
#include <is_graphs/AGraph.h>
#include <is_graphs/GraphMatch.h>
#include <is_graphs/SGraph.h>
#include <ros/ros.h>
#include <sys/wait.h>
#include <visualization_msgs/MarkerArray.h>

#include <array>
#include <cstdio>
#include <limits>
#include <mutex>

#include "../../src/ros/agraph_conversions.h"
#include "../../src/ros/graph_match_conversions.h"
#include "../../src/ros/sgraph_conversions.h"
#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/synthetic_sgraph.h"
#include "node_runner.h"

namespace is_graphs {
namespace {

class MatcherNodeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    match_sub_ = nh_.subscribe("graph_match", 10, &MatcherNodeTest::OnMatch, this);
    marker_sub_ = nh_.subscribe("graph_match/markers", 10, &MatcherNodeTest::OnMarkers, this);
    s_pub_ = nh_.advertise<is_graphs::SGraph>("s_graph", 10);
    const auto a =
        ros::topic::waitForMessage<is_graphs::AGraph>("a_graph", nh_, ros::Duration(180));
    ASSERT_TRUE(a) << "no a_graph within 180 s";
    a_graph_ = ros_conversions::FromMsg(*a);
    const ros::Time until = ros::Time::now() + ros::Duration(20);
    while (s_pub_.getNumSubscribers() == 0 && ros::Time::now() < until) ros::Duration(0.1).sleep();
    ASSERT_GT(s_pub_.getNumSubscribers(), 0u) << "matcher_node does not subscribe to s_graph";
  }

  void OnMatch(const is_graphs::GraphMatch::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    matches_.push_back(msg);
  }
  void OnMarkers(const visualization_msgs::MarkerArray::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    markers_ = msg;
  }

  /// Publishes `graph` as revision `revision` and waits for the graph_match of that revision.
  is_graphs::GraphMatch::ConstPtr Publish(sgraph::SGraph graph, unsigned revision) {
    graph.revision = revision;
    is_graphs::SGraph msg = ros_conversions::ToMsg(graph);
    msg.header.frame_id = "map";
    msg.header.stamp = ros::Time::now();
    s_pub_.publish(msg);
    const ros::Time until = ros::Time::now() + ros::Duration(30);
    while (ros::Time::now() < until) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        for (const auto& m : matches_)
          if (m->s_graph_revision == revision) return m;
      }
      ros::Duration(0.05).sleep();
    }
    return nullptr;
  }

  matching::SyntheticSGraph Synthetic(const std::vector<std::string>& names) {
    matching::SyntheticSGraphConfig c;
    for (const auto& r : a_graph_.rooms)
      if (names.empty() || std::find(names.begin(), names.end(), r.name) != names.end())
        c.rooms.push_back(r.id);
    c.bim_T_map = geometry::IsometryFromXYYaw(-8.0, 15.0, 2.2);
    c.normal_noise_deg = 0.5;
    c.offset_noise = 0.02;
    c.centre_noise = 0.05;
    c.seed = 5;
    return matching::MakeSyntheticSGraph(a_graph_, c);
  }

  ros::NodeHandle nh_;
  ros::Subscriber match_sub_, marker_sub_;
  ros::Publisher s_pub_;
  agraph::AGraph a_graph_;
  std::mutex mutex_;
  std::vector<is_graphs::GraphMatch::ConstPtr> matches_;
  visualization_msgs::MarkerArray::ConstPtr markers_;
};

TEST_F(MatcherNodeTest, UniqueAmbiguousAndMalformedSGraphs) {
  // 1. The whole building under a known motion: UNIQUE, right pairs, right motion, markers.
  const matching::SyntheticSGraph whole = Synthetic({});
  const auto unique = Publish(whole.graph, 1);
  ASSERT_TRUE(unique) << "no graph_match for revision 1";
  EXPECT_EQ(unique->status, is_graphs::GraphMatch::UNIQUE);
  EXPECT_EQ(unique->header.frame_id, "bim");
  EXPECT_EQ(unique->a_graph_sha256, a_graph_.source.sha256);
  EXPECT_EQ(unique->hypotheses, 1u);
  EXPECT_EQ(unique->room_pairs.size(), whole.graph.rooms.size());
  for (const auto& p : unique->room_pairs)
    EXPECT_EQ(static_cast<int>(p.a_id), whole.room_truth.at(static_cast<int>(p.s_id)));
  EXPECT_GT(unique->surface_pairs.size(), whole.graph.rooms.size());
  const matching::GraphMatch core = ros_conversions::FromMsg(*unique);
  EXPECT_NEAR(geometry::NormalizeAngle(geometry::Yaw(core.bim_T_map) - 2.2), 0.0, 0.02);
  EXPECT_LT((core.bim_T_map.translation().head<2>() - Eigen::Vector2d(-8.0, 15.0)).norm(), 0.3);
  {
    const ros::Time until = ros::Time::now() + ros::Duration(5);
    while (ros::Time::now() < until) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (markers_ && markers_->markers.size() > 2) break;
      }
      ros::Duration(0.05).sleep();
    }
    std::lock_guard<std::mutex> lock(mutex_);
    ASSERT_TRUE(markers_) << "no graph_match/markers";
    size_t room_lines = 0;
    for (const auto& m : markers_->markers) {
      EXPECT_EQ(m.header.frame_id, "bim");
      if (m.ns == "room_pairs") room_lines += m.points.size() / 2;
    }
    EXPECT_EQ(room_lines, whole.graph.rooms.size());
  }

  // 2. A lone rectangular room: it fits the building two ways at least (half a turn).
  const auto lone = Publish(Synthetic({"A"}).graph, 2);
  ASSERT_TRUE(lone);
  EXPECT_EQ(lone->status, is_graphs::GraphMatch::AMBIGUOUS);
  EXPECT_GE(lone->hypotheses, 2u);

  // 3. Malformed S-Graphs: no crash. Planes with NaN offsets and an empty graph: no UNIQUE.
  // Rooms without planes or with NaN centres are left out, the wall planes still match (the
  // corner proposals): if UNIQUE, then at the true motion and without room pairs.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<sgraph::SGraph> bad(4, whole.graph);
  for (auto& p : bad[0].planes) p.plane.d = nan;
  for (auto& r : bad[1].rooms) r.planes.clear();
  for (auto& r : bad[2].rooms) r.center.x() = nan;
  bad[3] = sgraph::SGraph{};
  for (size_t k = 0; k < bad.size(); ++k) {
    const auto m = Publish(bad[k], 10 + static_cast<unsigned>(k));
    ASSERT_TRUE(m) << "no graph_match for malformed S-Graph " << k << " (node down?)";
    if (k == 0 || k == 3) {
      EXPECT_NE(m->status, is_graphs::GraphMatch::UNIQUE) << "malformed S-Graph " << k;
    } else if (m->status == is_graphs::GraphMatch::UNIQUE) {
      EXPECT_TRUE(m->room_pairs.empty()) << "malformed S-Graph " << k;
      const matching::GraphMatch c = ros_conversions::FromMsg(*m);
      EXPECT_NEAR(geometry::NormalizeAngle(geometry::Yaw(c.bim_T_map) - 2.2), 0.0, 0.02) << k;
      EXPECT_LT((c.bim_T_map.translation().head<2>() - Eigen::Vector2d(-8.0, 15.0)).norm(), 0.3)
          << "malformed S-Graph " << k;
    }
  }

  // 4. Still alive and matching.
  const auto again = Publish(whole.graph, 20);
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, is_graphs::GraphMatch::UNIQUE);
}

std::pair<int, std::string> RunNode(const std::string& args) {
  return testing_support::RunNode(IS_GRAPHS_MATCHER_NODE, "bad_param_matcher", args);
}

TEST(MatcherNodeBadInput, BadParameterIsNamedAndStopsTheNode) {
  const auto [code, out] = RunNode("_offset_tolerance:=-1.0");
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("offset_tolerance"), std::string::npos) << out;
  const auto [code2, out2] = RunNode("_min_matched_rooms:=not_a_number");
  EXPECT_EQ(code2, 1) << out2;
  EXPECT_NE(out2.find("min_matched_rooms"), std::string::npos) << out2;
}

}  // namespace
}  // namespace is_graphs

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_matcher_node");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
