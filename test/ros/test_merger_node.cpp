// rostest of merger_node (with agraph_node on bim/rotated.ifc and matcher_node, wall time). The
// test plays the S-Graph node: synthetic S-Graphs made from the published A-Graph under a known
// B_T_M (one keyframe per room observing its planes, odometry drifted by a known map <- odom D)
// on `s_graph`, odometry on `odom` and tf map -> odom = D at 20 Hz. In order, on one merger:
//  1. on a fresh merger, a UNIQUE match for an S-Graph revision not seen yet (dropped after
//     match_wait, not used when that revision comes) and one for another A-Graph: neither
//     localizes, no pose_bim;
//  2. the matcher's UNIQUE match: LOCALIZED, pose_bim = B_T_M * D * odom, tf bim -> map = B_T_M;
//  3. the S-Graph restarts (lower revision, fewer keyframes): LOST, no pose_bim while LOST; its
//     next revision matched: LOCALIZED again, the pose on the new S-Graph's B_T_M;
//  4. odometry time going back: NOT_LOCALIZED, no pose_bim; then a forged match like those of 1
//     but right: LOCALIZED (so 1's were refused for their revision and A-Graph only).
// And a bad parameter stops the node, named.
#include <gtest/gtest.h>
#include <ros/ros.h>

#include <string>
#include <utility>
#include <vector>

#include "merger_node_fixture.h"
#include "node_runner.h"

namespace is_graphs {
namespace merger_test {
namespace {

TEST_F(MergerNodeTest, ContractOnGoodAndBadInput) {
  const std::string sha = a_graph_.source.sha256;
  const double t0 = ros::Time::now().toSec();
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(-8.0, 15.0, 2.2);
  const auto lone = Session({"A"}, truth, t0, 5);  // one rectangular room: AMBIGUOUS
  const auto all = Session({}, truth, t0, 5);

  // 1. Bad matches on a fresh merger.
  ASSERT_TRUE(WaitForState(Status::NOT_LOCALIZED, 5.0)) << "no localization_status";
  ASSERT_TRUE(Matched(lone, 1, false));
  match_pub_.publish(Forged(lone, 50, sha));  // revision 50 not seen: dropped after match_wait
  ros::WallDuration(3.0).sleep();
  ASSERT_TRUE(Matched(lone, 50, false));                       // ... and not used now
  match_pub_.publish(Forged(lone, 50, std::string(64, 'f')));  // another A-Graph
  ros::WallDuration(1.5).sleep();
  const auto changed = Poll(0.0, [&]() -> Status::ConstPtr {
    for (const auto& st : statuses_)
      if (st->state != Status::NOT_LOCALIZED) return st;
    return nullptr;
  });
  EXPECT_FALSE(changed) << "changed by a match for an unseen revision or A-Graph: "
                        << changed->message;
  EXPECT_EQ(PosesAfter(ros::Time(0)).size(), 0u) << "pose_bim before any usable match";

  // 2. The good path: the matcher's UNIQUE match.
  ASSERT_TRUE(Matched(all, 60, true));
  auto st = WaitForState(Status::LOCALIZED, 10.0);
  ASSERT_TRUE(st) << "not LOCALIZED on a UNIQUE match";
  ExpectPoseAfter(st->header.stamp, all, "good path");
  try {  // bim -> map puts the robot (map <- base_link: the newest keyframe) where pose_bim does
    const Eigen::Isometry3d& map_T_base = all.graph.keyframes.back().pose;
    ExpectNear(tf2::transformToEigen(
                   tf_buffer_.lookupTransform("bim", "map", ros::Time(0), ros::Duration(3.0))) *
                   map_T_base,
               truth * map_T_base, "tf bim -> map");
  } catch (const tf2::TransformException& e) {
    ADD_FAILURE() << "no tf bim -> map: " << e.what();
  }

  // 3. The S-Graph restarts (revision 2 < 60, one keyframe): LOST, no pose; matched again.
  const Eigen::Isometry3d truth2 = geometry::IsometryFromXYYaw(5.0, -3.0, -0.9);
  ASSERT_TRUE(Matched(Session({"A"}, truth2, t0 + 100, 6), 2, false));
  st = WaitForState(Status::LOST, 2.0);  // status_rate is 0.1 Hz: sent on the change
  ASSERT_TRUE(st) << "not LOST within 2 s of an S-Graph restart";
  ros::WallDuration(1.2).sleep();  // odometry at 20 Hz: stamped after LOST, never a pose
  EXPECT_TRUE(WaitForState(Status::LOST, 0.0)) << "LOST did not hold";
  EXPECT_EQ(PosesAfter(st->header.stamp).size(), 0u) << "pose_bim while LOST";
  const auto all2 = Session({}, truth2, t0 + 100, 6);
  ASSERT_TRUE(Matched(all2, 3, true));
  st = WaitForState(Status::LOCALIZED, 10.0);
  ASSERT_TRUE(st) << "not LOCALIZED again";
  ExpectPoseAfter(st->header.stamp, all2, "after the restart");

  // 4. Odometry time going back (a bag restarted): reset, no pose; then a right forged match.
  PublishOdometry(ros::Time::now() - ros::Duration(10.0));
  st = WaitForState(Status::NOT_LOCALIZED, 2.0);
  ASSERT_TRUE(st) << "no reset within 2 s of odometry time going back";
  ros::WallDuration(1.2).sleep();
  EXPECT_TRUE(WaitForState(Status::NOT_LOCALIZED, 0.0)) << "the reset did not hold";
  EXPECT_EQ(PosesAfter(st->header.stamp).size(), 0u) << "pose_bim after the reset";
  const auto lone3 = Session({"A"}, geometry::IsometryFromXYYaw(1.0, 2.0, 0.5), t0 + 200, 7);
  match_pub_.publish(Forged(lone3, 1, sha));  // before its revision: waits for it
  ros::WallDuration(0.3).sleep();
  ASSERT_TRUE(Matched(lone3, 1, false));
  st = WaitForState(Status::LOCALIZED, 10.0);
  ASSERT_TRUE(st) << "a right forged match was not used";
  ExpectPoseAfter(st->header.stamp, lone3, "forged match");
}

// A node that took the bad value would run on: `timeout` stops it after 20 s (exit code 124).
std::pair<int, std::string> RunNode(const std::string& args) {
  return testing_support::RunNode(std::string("timeout 20 ") + IS_GRAPHS_MERGER_NODE,
                                  "bad_merger_node", args);
}

TEST(MergerNodeBadInput, BadParameterIsNamedAndTheNodeExits) {
  for (const auto& [args, name] : std::vector<std::pair<std::string, std::string>>{
           {"_room_sigma:=-1.0", "room_sigma"},
           {"_min_inlier_fraction:=many", "min_inlier_fraction"},
           {"_status_rate:=-1.0", "status_rate"},
           {"_match_wait:=0", "match_wait"},
           {"_map_frame:=''", "map_frame"}}) {
    const auto [code, out] = RunNode(args);
    EXPECT_EQ(code, 1) << args << ": " << out;
    EXPECT_NE(out.find("parameter '/bad_merger_node_"), std::string::npos) << args << ": " << out;
    EXPECT_NE(out.find(name), std::string::npos) << args << ": " << out;
  }
}

}  // namespace
}  // namespace merger_test
}  // namespace is_graphs

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_merger_node");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
