// rostest of matcher_node's run-time requests (with agraph_node on bim/rotated.ifc, as
// test_matcher_node.cpp): a pose hint on `initialpose` and `set_pose_hint` (the robot's pose in
// the map from tf, here a static map -> base_link), rejected where the walls say otherwise,
// deciding a lone room's half-turn ambiguity; bad hints answered with a message naming what is
// wrong; `set_storey` and `relocalize`. Each request shows in the next graph_match (`hint`,
// `relocalizations`): the node matches the last S-Graph again at once.
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <gtest/gtest.h>
#include <is_graphs/AGraph.h>
#include <is_graphs/GraphMatch.h>
#include <is_graphs/SGraph.h>
#include <is_graphs/SetPoseHint.h>
#include <is_graphs/SetStorey.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include <functional>
#include <limits>
#include <mutex>

#include "../../src/ros/agraph_conversions.h"
#include "../../src/ros/pose_conversions.h"
#include "../../src/ros/sgraph_conversions.h"
#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/synthetic_sgraph.h"

namespace is_graphs {
namespace {

using Match = is_graphs::GraphMatch::ConstPtr;
const Eigen::Isometry3d kBimTMap = geometry::IsometryFromXYYaw(-8.0, 15.0, 2.2);
const Eigen::Isometry3d kMapTBase = geometry::IsometryFromXYYaw(1.0, 2.0, 0.3);
const Eigen::Isometry3d kBimTFloorplan = geometry::IsometryFromXYYaw(5.0, -1.0, M_PI / 2);

geometry_msgs::TransformStamped Tf(const std::string& parent, const std::string& child,
                                   const Eigen::Isometry3d& t) {
  geometry_msgs::TransformStamped m;
  m.header.stamp = ros::Time::now();
  m.header.frame_id = parent;
  m.child_frame_id = child;
  m.transform.translation.x = t.translation().x();
  m.transform.translation.y = t.translation().y();
  const Eigen::Quaterniond q(t.linear());
  m.transform.rotation.x = q.x(), m.transform.rotation.y = q.y();
  m.transform.rotation.z = q.z(), m.transform.rotation.w = q.w();
  return m;
}

/// The robot at `bim_T_base` in `frame` (given as bim <- base), 1 m and 20 deg.
geometry_msgs::PoseWithCovarianceStamped Hint(const Eigen::Isometry3d& frame_T_base,
                                              const std::string& frame = "bim") {
  geometry_msgs::PoseWithCovarianceStamped h;
  h.header.frame_id = frame;
  h.header.stamp = ros::Time::now();
  h.pose.pose = ros_conversions::ToPose(frame_T_base);
  h.pose.covariance[0] = h.pose.covariance[7] = 1.0;
  h.pose.covariance[35] = std::pow(20.0 * M_PI / 180.0, 2);
  return h;
}

class MatcherNodeHintTest : public ::testing::Test {
 protected:
  void SetUp() override {
    match_sub_ = nh_.subscribe("graph_match", 10, &MatcherNodeHintTest::OnMatch, this);
    s_pub_ = nh_.advertise<is_graphs::SGraph>("s_graph", 10);
    hint_pub_ = nh_.advertise<geometry_msgs::PoseWithCovarianceStamped>("initialpose", 1);
    tf_.sendTransform({Tf("map", "base_link", kMapTBase), Tf("bim", "floorplan", kBimTFloorplan)});
    const auto a =
        ros::topic::waitForMessage<is_graphs::AGraph>("a_graph", nh_, ros::Duration(180));
    ASSERT_TRUE(a) << "no a_graph within 180 s";
    a_graph_ = ros_conversions::FromMsg(*a);
    ASSERT_TRUE(ros::service::waitForService("set_pose_hint", ros::Duration(20)));
    const ros::Time until = ros::Time::now() + ros::Duration(20);
    while ((s_pub_.getNumSubscribers() == 0 || hint_pub_.getNumSubscribers() == 0) &&
           ros::Time::now() < until)
      ros::Duration(0.1).sleep();
    ASSERT_GT(hint_pub_.getNumSubscribers(), 0u) << "matcher_node does not subscribe initialpose";
  }

  void OnMatch(const Match& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    matches_.push_back(msg);
  }
  size_t Count() {
    std::lock_guard<std::mutex> lock(mutex_);
    return matches_.size();
  }
  /// The first graph_match after the `after`th that satisfies `ok` (null after 30 s).
  Match WaitFor(size_t after, const std::function<bool(const is_graphs::GraphMatch&)>& ok) {
    const ros::Time until = ros::Time::now() + ros::Duration(30);
    while (ros::Time::now() < until) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        for (size_t k = after; k < matches_.size(); ++k)
          if (ok(*matches_[k])) return matches_[k];
      }
      ros::Duration(0.05).sleep();
    }
    return nullptr;
  }
  Match Publish(const std::vector<std::string>& rooms, unsigned revision) {
    matching::SyntheticSGraphConfig c;
    for (const auto& r : a_graph_.rooms)
      if (rooms.empty() || std::find(rooms.begin(), rooms.end(), r.name) != rooms.end())
        c.rooms.push_back(r.id);
    c.bim_T_map = kBimTMap;
    c.seed = 5;
    sgraph::SGraph graph = matching::MakeSyntheticSGraph(a_graph_, c).graph;
    graph.revision = revision;
    is_graphs::SGraph msg = ros_conversions::ToMsg(graph);
    msg.header.frame_id = "map";
    msg.header.stamp = ros::Time::now();
    const size_t before = Count();
    s_pub_.publish(msg);
    return WaitFor(before,
                   [&](const is_graphs::GraphMatch& m) { return m.s_graph_revision == revision; });
  }
  is_graphs::SetPoseHint::Response SetHint(const geometry_msgs::PoseWithCovarianceStamped& h,
                                           const std::string& storey = "") {
    is_graphs::SetPoseHint srv;
    srv.request.pose = h;
    srv.request.storey = storey;
    EXPECT_TRUE(ros::service::call("set_pose_hint", srv));
    return srv.response;
  }

  ros::NodeHandle nh_;
  ros::Subscriber match_sub_;
  ros::Publisher s_pub_, hint_pub_;
  tf2_ros::StaticTransformBroadcaster tf_;
  agraph::AGraph a_graph_;
  std::mutex mutex_;
  std::vector<Match> matches_;
};

bool Starts(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

TEST_F(MatcherNodeHintTest, HintsRelocalizeAndStorey) {
  const Eigen::Isometry3d truth = kBimTMap * kMapTBase;  // the robot in bim
  ASSERT_TRUE(Publish({}, 1));
  // 1. On initialpose, 10 m off: the walls say otherwise (UNIQUE elsewhere): rejected, why.
  size_t n = Count();
  hint_pub_.publish(Hint(Eigen::Translation3d(10.0, 0.0, 0.0) * truth));
  Match m = WaitFor(n, [](const auto& g) { return !g.hint.empty(); });
  ASSERT_TRUE(m) << "no graph_match after a hint on initialpose";
  EXPECT_TRUE(Starts(m->hint, "rejected: ")) << m->hint;
  EXPECT_NE(m->hint.find("sigma from the hint"), std::string::npos) << m->hint;
  EXPECT_EQ(m->status, is_graphs::GraphMatch::UNIQUE);

  // 2. A lone room fits two ways (a half turn); a hint in one decides, in another frame too.
  m = Publish({"A"}, 2);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->status, is_graphs::GraphMatch::AMBIGUOUS);
  n = Count();
  const auto taken = SetHint(Hint(kBimTFloorplan.inverse() * truth, "floorplan"));
  EXPECT_TRUE(taken.success) << taken.message;
  m = WaitFor(n, [](const auto& g) { return Starts(g.hint, "in force"); });
  ASSERT_TRUE(m) << "no graph_match with the hint in force";
  EXPECT_EQ(m->status, is_graphs::GraphMatch::UNIQUE) << m->hint;
  const Eigen::Isometry3d got = ros_conversions::FromPose(m->bim_T_map);
  EXPECT_LT((got.translation() - kBimTMap.translation()).head<2>().norm(), 0.3);

  // 3. Bad hints: a message naming what is wrong, nothing changed (still the hint above).
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto bad = Hint(truth, "nowhere");
  EXPECT_NE(SetHint(bad).message.find("'nowhere'"), std::string::npos);
  bad = Hint(truth);
  bad.pose.pose.position.x = nan;
  EXPECT_NE(SetHint(bad).message.find("not finite"), std::string::npos);
  bad = Hint(truth);
  bad.pose.covariance[35] = 0.0;
  EXPECT_NE(SetHint(bad).message.find("not positive definite"), std::string::npos);
  const auto attic = SetHint(Hint(truth), "Attic");
  EXPECT_FALSE(attic.success);
  EXPECT_NE(attic.message.find("Attic"), std::string::npos) << attic.message;

  // 4. set_storey: an unknown one refused; the whole building again: matched again at once.
  is_graphs::SetStorey storey;
  storey.request.storey = "Attic";
  ASSERT_TRUE(ros::service::call("set_storey", storey));
  EXPECT_FALSE(storey.response.success);
  EXPECT_NE(storey.response.message.find("Attic"), std::string::npos);
  n = Count();
  storey.request.storey = "";
  ASSERT_TRUE(ros::service::call("set_storey", storey));
  EXPECT_TRUE(storey.response.success) << storey.response.message;
  m = WaitFor(n, [](const auto& g) { return g.relocalizations == 1; });
  ASSERT_TRUE(m) << "no graph_match after set_storey";
  EXPECT_EQ(m->status, is_graphs::GraphMatch::UNIQUE) << "the hint holds over set_storey";

  // 5. relocalize: the hint forgotten, the lone room AMBIGUOUS again, the merger told.
  n = Count();
  std_srvs::Trigger relocalize;
  ASSERT_TRUE(ros::service::call("relocalize", relocalize));
  EXPECT_TRUE(relocalize.response.success);
  m = WaitFor(n, [](const auto& g) { return g.relocalizations == 2; });
  ASSERT_TRUE(m) << "no graph_match after relocalize";
  EXPECT_EQ(m->hint, "");
  EXPECT_EQ(m->status, is_graphs::GraphMatch::AMBIGUOUS);
}

}  // namespace
}  // namespace is_graphs
