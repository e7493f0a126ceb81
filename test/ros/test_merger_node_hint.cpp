// rostest of merger_node with matcher_node's run-time requests (merger_node.test, the fixture of
// test_merger_node.cpp): `relocalize` on matcher_node drops the merge (NOT_LOCALIZED at once,
// through graph_match.relocalizations); a pose hint on `set_pose_hint` decides a lone room's
// half-turn ambiguity, and `localization_status` says the hint is in force.
#include <gtest/gtest.h>
#include <is_graphs/SetPoseHint.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include <string>

#include "merger_node_fixture.h"

namespace is_graphs {
namespace merger_test {
namespace {

TEST_F(MergerNodeTest, RelocalizeAndAPoseHintReachTheStatus) {
  const double t0 = ros::Time::now().toSec();
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(-8.0, 15.0, 2.2);
  const auto lone = Session({"A"}, truth, t0 + 300, 8);  // one rectangular room: AMBIGUOUS
  const auto all = Session({}, truth, t0 + 300, 8);
  ASSERT_TRUE(Matched(all, 300, true));
  ASSERT_TRUE(WaitForState(Status::LOCALIZED, 10.0)) << "not LOCALIZED on a UNIQUE match";

  // 1. relocalize: the merge dropped at once (status_rate is 0.1 Hz: sent on the change).
  ASSERT_TRUE(Matched(lone, 301, false));
  std_srvs::Trigger relocalize;
  ASSERT_TRUE(ros::service::call("relocalize", relocalize));
  EXPECT_TRUE(relocalize.response.success);
  Status::ConstPtr st = WaitForState(Status::NOT_LOCALIZED, 3.0);
  ASSERT_TRUE(st) << "not NOT_LOCALIZED within 3 s of relocalize";
  EXPECT_NE(st->message.find("relocalize"), std::string::npos) << st->message;
  EXPECT_FALSE(st->hint_in_force);

  // 2. A hint at the robot (0.3 m off): UNIQUE, LOCALIZED with the hint in force. The robot's
  // pose in the map at the hint's stamp: tf map -> odom (the fixture's D) and odom -> base_link.
  tf2_ros::StaticTransformBroadcaster static_tf;
  geometry_msgs::TransformStamped odom_base =
      tf2::eigenToTransform(lone.graph.keyframes.back().odom_pose);
  odom_base.header.stamp = ros::Time::now();
  odom_base.header.frame_id = "odom";
  odom_base.child_frame_id = "base_link";
  static_tf.sendTransform(odom_base);
  ros::WallDuration(0.3).sleep();
  is_graphs::SetPoseHint hint;
  hint.request.pose.header.frame_id = "bim";
  hint.request.pose.header.stamp = ros::Time::now();
  hint.request.pose.pose.pose = ros_conversions::ToPose(Eigen::Translation3d(0.3, 0.0, 0.0) *
                                                        truth * lone.graph.keyframes.back().pose);
  hint.request.pose.pose.covariance[0] = hint.request.pose.pose.covariance[7] = 1.0;
  hint.request.pose.pose.covariance[35] = std::pow(20.0 * kDeg, 2);
  ASSERT_TRUE(ros::service::call("set_pose_hint", hint));
  ASSERT_TRUE(hint.response.success) << hint.response.message;
  st = Poll(10.0, [&]() -> Status::ConstPtr {
    return !statuses_.empty() && statuses_.back()->state == Status::LOCALIZED ? statuses_.back()
                                                                              : nullptr;
  });
  ASSERT_TRUE(st) << "not LOCALIZED with the hint";
  ExpectPoseAfter(st->header.stamp, lone, "with the hint");
  st = Poll(12.0, [&]() -> Status::ConstPtr {  // the next status (0.1 Hz) or at once
    return !statuses_.empty() && statuses_.back()->hint_in_force ? statuses_.back() : nullptr;
  });
  ASSERT_TRUE(st) << "localization_status never says the hint is in force";
  EXPECT_EQ(st->hint.rfind("in force", 0), 0u) << st->hint;

  // 3. relocalize forgets the hint too: the lone room AMBIGUOUS again, no merge.
  ASSERT_TRUE(ros::service::call("relocalize", relocalize));
  st = Poll(3.0, [&]() -> Status::ConstPtr {
    return !statuses_.empty() && statuses_.back()->state == Status::NOT_LOCALIZED &&
                   !statuses_.back()->hint_in_force
               ? statuses_.back()
               : nullptr;
  });
  ASSERT_TRUE(st) << "not NOT_LOCALIZED without the hint after relocalize";
}

}  // namespace
}  // namespace merger_test
}  // namespace is_graphs
