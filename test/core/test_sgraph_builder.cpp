#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "is_graphs/sgraph/sgraph_builder.h"
#include "sgraph_test_helpers.h"

namespace is_graphs {
namespace sgraph {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

// A robot walking along x through an 8 x 5 m room (floor at z = 0, base_link 0.5 m up) while
// its odometry drifts in yaw; the sensor sees the true room.
class BuilderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::mt19937 rng(5);
    world_ = testing::PolygonRoom({{0, 0}, {8, 0}, {8, 5}, {0, 5}}, 0.05, 0.01, rng);
    testing::AddFloor(world_, 0.1, 7.9, 0.1, 4.9, 0.0, 0.1, 0.01, rng);
  }
  static Eigen::Isometry3d Truth(double t) {
    Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
    p.translation() = Vector3d(1.0 + 0.5 * t, 2.5, 0.5);
    return p;
  }
  static Eigen::Isometry3d Odom(double t) {
    // Yaw drifts by 0.03 rad per metre walked, and the distance is 3 % long.
    const Eigen::Isometry3d truth = Truth(t);
    const double s = 0.5 * t;
    Eigen::Isometry3d o = Eigen::Isometry3d::Identity();
    o.linear() = Eigen::AngleAxisd(0.03 * s, Vector3d::UnitZ()).toRotationMatrix();
    o.translation() =
        Vector3d(1.0 + 1.03 * s * std::cos(0.015 * s), 1.03 * s * std::sin(0.015 * s) + 2.5, 0.5);
    (void)truth;
    return o;
  }
  Scan MakeScan(double t) const {
    Scan scan;
    scan.stamp = kStart + t;
    scan.frame_id = "velodyne";
    scan.has_time = false;
    const Eigen::Isometry3f sensor_T_world = Truth(t).inverse().cast<float>();
    for (const auto& p : world_) {
      const Eigen::Vector3f q = sensor_T_world * p;
      if (q.norm() > 15.0f || std::abs(q.z()) > 0.4f * q.head<2>().norm() + 0.01f)
        continue;  // ±22°
      ScanPoint sp;
      sp.x = q.x(), sp.y = q.y(), sp.z = q.z();
      scan.points.push_back(sp);
    }
    return scan;
  }
  // Feeds odometry at 50 Hz and scans at 10 Hz for `seconds`; optimizes after keyframes.
  void Run(SGraphBuilder& builder, double seconds) {
    for (int i = 0; i <= seconds * 50; ++i) {
      const double t = i / 50.0;
      builder.AddOdometry(kStart + t, Odom(t));
      if (i % 5 == 0 && i > 0) {
        const auto r = builder.AddScan(MakeScan(t - 0.02), Eigen::Isometry3d::Identity());
        if (r.status == SGraphBuilder::ScanStatus::kKeyframe) builder.Optimize();
      }
    }
  }
  static constexpr double kStart = 1000.0;
  PointList world_;
};

TEST_F(BuilderTest, MapsTheRoomAndCorrectsTheDrift) {
  SGraphBuilder builder(FrontendConfig{}, BackendConfig{});
  Run(builder, 12.0);  // 6 m
  const SGraph g = builder.Snapshot();
  ASSERT_GE(g.keyframes.size(), 6u);
  EXPECT_GT(g.revision, 0u);
  // Four walls and the floor; a few extra planes at most (no duplicates of the big walls).
  int walls = 0, floors = 0;
  for (const auto& p : g.planes)
    (p.orientation == geometry::Orientation::kHorizontal ? floors : walls)++;
  EXPECT_EQ(floors, 1);
  EXPECT_GE(walls, 4);
  EXPECT_LE(walls, 6);
  // The trajectory: optimized keyframes closer to the truth than odometry (gauge: the first).
  double odom_error = 0.0, graph_error = 0.0;
  for (const auto& k : g.keyframes) {
    const double t = k.stamp - kStart;
    odom_error = std::max(odom_error, (k.odom_pose.translation() - Truth(t).translation()).norm());
    graph_error = std::max(graph_error, (k.pose.translation() - Truth(t).translation()).norm());
  }
  EXPECT_LT(graph_error, 0.5 * odom_error) << "odometry " << odom_error << " m";
  EXPECT_LT(graph_error, 0.05);
  // The room, a four-wall one, centred at (4, 2.5), on the floor.
  ASSERT_EQ(g.rooms.size(), 1u);
  EXPECT_EQ(g.rooms[0].type, RoomType::kRoom);
  EXPECT_LT((g.rooms[0].center.head<2>() - Vector2d(4, 2.5)).norm(), 0.1);
  // Its centre is where the mid-lines meet: published with room_sigma, not the looser
  // polygon_room_sigma of a centroid.
  const double room_sigma = BackendConfig{}.room_sigma;
  EXPECT_NEAR(g.rooms[0].information(0, 0), 1.0 / (room_sigma * room_sigma), 1e-9);
  ASSERT_EQ(g.floors.size(), 1u);
  EXPECT_NEAR(g.floors[0].height, 0.0, 0.03);
  // map -> odom undoes the drift at the last keyframe.
  const Eigen::Isometry3d last = builder.MapToOdom() * g.keyframes.back().odom_pose;
  EXPECT_LT((last.translation() - g.keyframes.back().pose.translation()).norm(), 1e-9);
  EXPECT_FALSE(builder.MapCloud(0.2).empty());
}

// A window of 2 keyframes (BackendConfig::window_keyframes): the older keyframes are held, the
// result stays as good as the whole graph's, and the clouds out of the window are thinned.
TEST_F(BuilderTest, AWindowedBackEndMapsTheRoomAsWellAndThinsOldClouds) {
  BackendConfig windowed;
  windowed.window_keyframes = 2;
  windowed.window_cloud_voxel_size = 0.3;
  SGraphBuilder small(FrontendConfig{}, windowed), whole(FrontendConfig{}, BackendConfig{});
  Run(small, 12.0);
  Run(whole, 12.0);
  const SGraph a = small.Snapshot(), b = whole.Snapshot();
  ASSERT_EQ(a.keyframes.size(), b.keyframes.size());
  ASSERT_GE(a.keyframes.size(), 6u);
  double error = 0.0, apart = 0.0;
  for (size_t i = 0; i < a.keyframes.size(); ++i) {
    const Vector3d p = a.keyframes[i].pose.translation();
    error = std::max(error, (p - Truth(a.keyframes[i].stamp - kStart).translation()).norm());
    apart = std::max(apart, (p - b.keyframes[i].pose.translation()).norm());
  }
  EXPECT_LT(error, 0.05);
  EXPECT_LT(apart, 0.03);
  ASSERT_EQ(a.rooms.size(), 1u);
  EXPECT_LT((a.rooms[0].center.head<2>() - Vector2d(4, 2.5)).norm(), 0.1);
  // The old keyframes' clouds are thinned to 0.3 m; the map cloud still covers the room.
  EXPECT_LT(small.num_cloud_points(), whole.num_cloud_points() / 2);
  EXPECT_GT(small.MapCloud(0.2).size(), whole.MapCloud(0.2).size() / 2);
}

TEST_F(BuilderTest, BadInputIsSkippedWithAWarning) {
  SGraphBuilder builder(FrontendConfig{}, BackendConfig{});
  // A scan before any odometry.
  auto r = builder.AddScan(MakeScan(0.0), Eigen::Isometry3d::Identity());
  EXPECT_EQ(r.status, SGraphBuilder::ScanStatus::kSkipped);
  EXPECT_NE(r.warning.find("no odometry"), std::string::npos) << r.warning;
  for (int i = 0; i <= 50; ++i) builder.AddOdometry(kStart + i / 50.0, Odom(i / 50.0));
  // Empty cloud.
  Scan empty;
  empty.stamp = kStart + 0.5;
  r = builder.AddScan(empty, Eigen::Isometry3d::Identity());
  EXPECT_EQ(r.status, SGraphBuilder::ScanStatus::kSkipped);
  EXPECT_NE(r.warning.find("empty"), std::string::npos);
  // All points NaN / infinite.
  Scan bad = MakeScan(0.5);
  for (auto& p : bad.points) p.x = std::numeric_limits<float>::quiet_NaN();
  bad.points[0].y = std::numeric_limits<float>::infinity();
  r = builder.AddScan(bad, Eigen::Isometry3d::Identity());
  EXPECT_EQ(r.status, SGraphBuilder::ScanStatus::kSkipped);
  EXPECT_EQ(builder.num_keyframes(), 0);
  // Some NaN points: the scan is used, the points dropped.
  Scan some = MakeScan(0.6);
  some.points[0].z = std::numeric_limits<float>::quiet_NaN();
  r = builder.AddScan(some, Eigen::Isometry3d::Identity());
  EXPECT_EQ(r.status, SGraphBuilder::ScanStatus::kKeyframe) << r.warning;
  EXPECT_NE(r.warning.find("non-finite"), std::string::npos);
  // A gap in odometry: scans inside it are skipped.
  auto o = builder.AddOdometry(kStart + 5.0, Odom(5.0));
  EXPECT_NE(o.warning.find("gap"), std::string::npos);
  r = builder.AddScan(MakeScan(3.0), Eigen::Isometry3d::Identity());
  EXPECT_EQ(r.status, SGraphBuilder::ScanStatus::kSkipped);
  // Time going backwards (a restarted bag): the graph is reset, not corrupted.
  o = builder.AddOdometry(kStart - 100.0, Odom(0.0));
  EXPECT_TRUE(o.reset);
  EXPECT_EQ(builder.num_keyframes(), 0);
  EXPECT_TRUE(builder.Snapshot().planes.empty());
  EXPECT_FALSE(builder.Optimize().usable);
}

// Kidnapped: after walking the room the robot is carried (odometry holds) into a room turned
// 35 degrees: within the track check period the S-Graph restarts from that scan, holding the
// new room only; nothing of the old map is tied to it. Walking the room alone never restarts.
TEST_F(BuilderTest, ACarriedRobotRestartsTheGraphInsteadOfCorruptingIt) {
  for (bool detect : {true, false}) {
    SCOPED_TRACE(detect ? "track loss detected" : "detect_track_loss off");
    FrontendConfig config;
    config.detect_track_loss = detect;
    SGraphBuilder builder(config, BackendConfig{});
    int restarts = 0;
    for (int i = 0; i <= 12 * 50; ++i) {
      const double t = i / 50.0;
      builder.AddOdometry(kStart + t, Odom(t));
      if (i % 5 || i == 0) continue;
      const auto r = builder.AddScan(MakeScan(t - 0.02), Eigen::Isometry3d::Identity());
      restarts += r.restarted;
      if (r.status == SGraphBuilder::ScanStatus::kKeyframe) builder.Optimize();
    }
    EXPECT_EQ(restarts, 0);
    const int before = builder.num_keyframes();
    ASSERT_GE(before, config.track_loss_min_keyframes);
    // The other room: an L of six walls, 5 x 3.6 m, around where the robot now stands
    // (x = 7, y = 2.5), turned.
    std::mt19937 rng(6);
    const Eigen::Rotation2Dd turn(35.0 * M_PI / 180.0);
    std::vector<Vector2d> corners;
    for (const Vector2d& c : {Vector2d(-2.5, -1.8), Vector2d(2.5, -1.8), Vector2d(2.5, 0.4),
                              Vector2d(0.8, 0.4), Vector2d(0.8, 1.8), Vector2d(-2.5, 1.8)})
      corners.push_back(Vector2d(7.0, 2.5) + turn * c);
    world_ = testing::PolygonRoom(corners, 0.05, 0.01, rng);
    double restarted_at = -1.0;
    for (int i = 1; i <= 3 * 50; ++i) {  // standing there for 3 s
      const double t = 12.0 + i / 50.0;
      builder.AddOdometry(kStart + t, Odom(12.0));
      if (i % 5) continue;
      Scan scan = MakeScan(12.0);
      scan.stamp = kStart + t - 0.02;
      const auto r = builder.AddScan(scan, Eigen::Isometry3d::Identity());
      if (!r.restarted) continue;
      EXPECT_LT(restarted_at, 0.0) << "restarted twice";
      restarted_at = t - 12.0;
      EXPECT_EQ(r.status, SGraphBuilder::ScanStatus::kKeyframe);
      EXPECT_NE(r.warning.find("track lost"), std::string::npos) << r.warning;
      EXPECT_GE(r.num_walls, config.track_loss_min_walls);
    }
    if (!detect) {
      EXPECT_LT(restarted_at, 0.0);
      EXPECT_EQ(builder.num_keyframes(), before);
      continue;
    }
    ASSERT_GE(restarted_at, 0.0) << "the carry was not detected";
    EXPECT_LE(restarted_at, config.track_check_period + 0.15);
    EXPECT_EQ(builder.num_keyframes(), 1);
    builder.Optimize();
    const SGraph g = builder.Snapshot();
    ASSERT_EQ(g.keyframes.size(), 1u);
    EXPECT_TRUE(g.rooms.empty() || g.rooms.size() == 1u);
    // The graph restarts in the odometry frame: the turned room's walls (normals at 35 and 125
    // degrees in the world) appear turned further by the odometry's yaw error at 12 s.
    const Eigen::Matrix3d odom_rotation = Odom(12.0).linear();
    const double expected =
        35.0 + std::atan2(odom_rotation(1, 0), odom_rotation(0, 0)) * 180.0 / M_PI;
    int walls = 0;
    for (const auto& p : g.planes) {
      if (p.orientation == geometry::Orientation::kHorizontal) continue;
      ++walls;
      // Every wall mapped now is one of the turned room's, none of the first room's.
      const double a = std::atan2(p.plane.normal.y(), p.plane.normal.x()) * 180.0 / M_PI;
      const double off = std::fmod(std::abs(a - expected) + 360.0, 90.0);
      EXPECT_LT(std::min(off, 90.0 - off), 3.0) << "plane " << p.id << " at " << a << " deg";
    }
    EXPECT_GE(walls, config.track_loss_min_walls);
  }
}

TEST(FrontendConfigTrackLoss, BadValuesAreNamed) {
  FrontendConfig c;
  c.track_loss_new_share = 0.3;
  EXPECT_NE(c.Validate().find("track_loss_new_share"), std::string::npos) << c.Validate();
  c = FrontendConfig();
  c.track_check_period = -1.0;
  EXPECT_NE(c.Validate().find("track_check_period"), std::string::npos) << c.Validate();
  c = FrontendConfig();
  c.track_loss_min_walls = 0;
  EXPECT_NE(c.Validate().find("track_loss_min_walls"), std::string::npos) << c.Validate();
}

}  // namespace
}  // namespace sgraph
}  // namespace is_graphs
