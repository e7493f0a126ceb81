// rostest of the whole pipeline (agraph_node, sgraph_node, matcher_node, merger_node) on a short
// bag with simulated time: no pose_bim before LOCALIZED, localized before the bag ends, the APE
// (x, y) of pose_bim against ground_truth/pose without alignment, the yaw error, tf bim -> map;
// and the real merger_node binary on bad parameters.
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <gtest/gtest.h>
#include <is_graphs/LocalizationStatus.h>
#include <ros/ros.h>
#include <sys/wait.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <vector>

#include "../../src/ros/pose_conversions.h"
#include "is_graphs/geometry/se3.h"
#include "node_runner.h"

namespace is_graphs {
namespace {

// The APE bound on x, y after localization: the target, 0.05 m. Measured on this bag
// (D5_rotated at half duration, 2x), two runs: RMSE 0.018 / 0.025 m, max 0.052 / 0.064 m;
// yaw max 0.32 / 1.4°. Yaw: RMSE within the 1°, no single pose beyond 2°.
constexpr double kMaxApeXY = 0.05;
constexpr double kMaxYawRmseDeg = 1.0;
constexpr double kMaxYawDeg = 2.0;  // transients when the S-Graph re-solves (see the report)

class LocalizeTest : public ::testing::Test {
 protected:
  // Collects pose_bim, localization_status and ground truth until the bag has played.
  static void SetUpTestSuite() {
    ros::NodeHandle nh;
    ros::Subscriber ps = nh.subscribe<geometry_msgs::PoseWithCovarianceStamped>(
        "pose_bim", 1000,
        boost::function<void(const geometry_msgs::PoseWithCovarianceStamped::ConstPtr&)>(
            [](const geometry_msgs::PoseWithCovarianceStamped::ConstPtr& m) {
              std::lock_guard<std::mutex> lock(mutex_);
              poses_.push_back(*m);
              if (!localized_seen_) ++poses_before_status_;
            }));
    ros::Subscriber ss = nh.subscribe<is_graphs::LocalizationStatus>(
        "localization_status", 100,
        boost::function<void(const is_graphs::LocalizationStatus::ConstPtr&)>(
            [](const is_graphs::LocalizationStatus::ConstPtr& m) {
              std::lock_guard<std::mutex> lock(mutex_);
              statuses_.push_back(*m);
              if (m->state == is_graphs::LocalizationStatus::LOCALIZED && !localized_seen_) {
                localized_seen_ = true;
                first_localized_ = *m;
              }
            }));
    ros::Subscriber ts = nh.subscribe<geometry_msgs::PoseStamped>(
        "ground_truth/pose", 2000,
        boost::function<void(const geometry_msgs::PoseStamped::ConstPtr&)>(
            [](const geometry_msgs::PoseStamped::ConstPtr& m) {
              std::lock_guard<std::mutex> lock(mutex_);
              truth_[m->header.stamp.toNSec()] = ros_conversions::FromPose(m->pose);
              last_truth_wall_ = ros::WallTime::now();
            }));
    tf_ = new tf2_ros::Buffer(ros::Duration(60.0));
    listener_ = new tf2_ros::TransformListener(*tf_);
    const ros::WallTime start = ros::WallTime::now();
    while (ros::ok() && (ros::WallTime::now() - start).toSec() < 150.0) {
      ros::WallDuration(0.2).sleep();
      std::lock_guard<std::mutex> lock(mutex_);
      if (!truth_.empty() && (ros::WallTime::now() - last_truth_wall_).toSec() > 4.0) break;
    }
    std::string error;
    // No timeout: simulated time stands still once the bag is over.
    tf_ok_ = tf_->canTransform("bim", "map", ros::Time(0), &error);
    tf_error_ = error;
  }
  static inline std::mutex mutex_;
  static inline std::vector<geometry_msgs::PoseWithCovarianceStamped> poses_;
  static inline std::vector<is_graphs::LocalizationStatus> statuses_;
  static inline std::map<uint64_t, Eigen::Isometry3d> truth_;
  static inline ros::WallTime last_truth_wall_;
  static inline bool localized_seen_ = false;
  static inline int poses_before_status_ = 0;
  static inline is_graphs::LocalizationStatus first_localized_;
  static inline tf2_ros::Buffer* tf_ = nullptr;
  static inline tf2_ros::TransformListener* listener_ = nullptr;
  static inline bool tf_ok_ = false;
  static inline std::string tf_error_;
};

TEST_F(LocalizeTest, LocalizesBeforeTheBagEndsAndNeverPublishesBefore) {
  std::lock_guard<std::mutex> lock(mutex_);
  ASSERT_FALSE(truth_.empty()) << "no ground truth: the bag did not play";
  ASSERT_FALSE(statuses_.empty()) << "no localization_status";
  EXPECT_EQ(statuses_.front().state, is_graphs::LocalizationStatus::NOT_LOCALIZED);
  ASSERT_TRUE(localized_seen_) << "not localized; last status: " << statuses_.back().message;
  EXPECT_EQ(statuses_.back().state, is_graphs::LocalizationStatus::LOCALIZED)
      << statuses_.back().message;
  const double since = first_localized_.localized_since.toSec();
  for (const auto& p : poses_)
    EXPECT_GE(p.header.stamp.toSec(), since - 1e-6) << "pose_bim before the first merge";
  EXPECT_LE(poses_before_status_, 5) << "pose_bim arrived before the LOCALIZED status";
  ASSERT_GT(poses_.size(), 50u) << "too few pose_bim after localization";
  const double bag_end = (truth_.rbegin()->first) * 1e-9;
  EXPECT_LT(since, bag_end);
  std::printf(
      "[ localize ] localized %.1f s after start, after %.1f m, at t = %.1f (bag end %.1f)\n",
      first_localized_.seconds_to_localize, first_localized_.distance_to_localize, since, bag_end);
  for (int i = 0; i < 36; i += 7) EXPECT_GT(first_localized_.covariance[i], 0.0);
}

TEST_F(LocalizeTest, PoseInTheBimMatchesGroundTruth) {
  std::lock_guard<std::mutex> lock(mutex_);
  ASSERT_FALSE(poses_.empty());
  double sum_sq = 0.0, max_xy = 0.0, max_yaw = 0.0, sum_yaw_sq = 0.0;
  int n = 0;
  for (const auto& p : poses_) {
    auto it = truth_.lower_bound(p.header.stamp.toNSec());
    if (it == truth_.end()) continue;
    if (std::abs(static_cast<double>(it->first) - p.header.stamp.toNSec()) > 5e6) continue;
    const Eigen::Isometry3d est = ros_conversions::FromPose(p.pose.pose);
    const Eigen::Vector2d e = (est.translation() - it->second.translation()).head<2>();
    sum_sq += e.squaredNorm();
    max_xy = std::max(max_xy, e.norm());
    const double yaw = geometry::NormalizeAngle(geometry::Yaw(est) - geometry::Yaw(it->second));
    max_yaw = std::max(max_yaw, std::abs(yaw));
    sum_yaw_sq += yaw * yaw;
    ++n;
  }
  ASSERT_GT(n, 50) << "pose_bim stamps do not meet ground truth stamps";
  const double rmse = std::sqrt(sum_sq / n);
  const double yaw_rmse_deg = std::sqrt(sum_yaw_sq / n) * 180.0 / M_PI;
  std::printf(
      "[ localize ] APE x,y: RMSE %.4f m, max %.4f m over %d poses; yaw RMSE %.3f deg, "
      "max %.3f deg\n",
      rmse, max_xy, n, yaw_rmse_deg, max_yaw * 180.0 / M_PI);
  EXPECT_LT(yaw_rmse_deg, kMaxYawRmseDeg);
  EXPECT_LT(rmse, kMaxApeXY);
  EXPECT_LT(max_yaw * 180.0 / M_PI, kMaxYawDeg);
}

TEST_F(LocalizeTest, BroadcastsBimToMap) { EXPECT_TRUE(tf_ok_) << tf_error_; }

std::pair<int, std::string> RunNode(const std::string& args) {
  return testing_support::RunNode(IS_GRAPHS_MERGER_NODE, "bad_merger_node", args);
}

TEST(MergerNodeBadInput, BadParameterIsNamedAndTheNodeExits) {
  auto [code, out] = RunNode("_room_sigma:=-1.0");
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("room_sigma"), std::string::npos) << out;
  std::tie(code, out) = RunNode("_min_inlier_fraction:=many");
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("min_inlier_fraction"), std::string::npos) << out;
}

}  // namespace
}  // namespace is_graphs

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_localize");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
