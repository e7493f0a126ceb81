// The windowed S-Graph back end (BackendConfig::window_keyframes, backend_window.h): its
// problem stays the same size however many keyframes the graph holds, and online (one
// optimization after each keyframe, as SGraphBuilder runs it) it lands where the whole graph's
// optimization does.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "is_graphs/sgraph/backend_window.h"
#include "is_graphs/sgraph/sgraph_backend.h"

namespace is_graphs {
namespace sgraph {
namespace {

// A corridor along x between walls y = ±1.5 (planes 0, 1, seen from everywhere) with a cross
// wall every 5 m (plane 2 + j at x = 5 (j + 1), seen from up to 6 m before it). The robot walks
// along x in 0.5 m steps with a little sway; its odometry reads 2 % long with noise.
struct Corridor {
  std::vector<geometry::Plane> walls;
  std::vector<Eigen::Isometry3d> truth;
  std::mt19937 rng{7};

  geometry::Plane Wall(int id) {
    while (static_cast<int>(walls.size()) <= id) {
      const int j = static_cast<int>(walls.size()) - 2;
      walls.push_back(j == -2   ? geometry::Plane(-Eigen::Vector3d::UnitY(), -1.5)
                      : j == -1 ? geometry::Plane(Eigen::Vector3d::UnitY(), -1.5)
                                : geometry::Plane(-Eigen::Vector3d::UnitX(), -5.0 * (j + 1)));
    }
    return walls[id];
  }
  std::vector<int> Seen(const Eigen::Isometry3d& pose) {
    std::vector<int> ids{0, 1};
    const double x = pose.translation().x();
    for (int j = static_cast<int>(std::floor(x / 5.0)); j * 5.0 + 5.0 - x < 6.0; ++j)
      if (j >= 0 && j * 5.0 + 5.0 > x + 0.2) ids.push_back(2 + j);
    return ids;
  }
  /// Appends keyframe k (pose predicted by the odometry from the previous estimate), its
  /// observations, and a plane first seen (at the prediction).
  void Append(BackendProblem& p) {
    const int k = static_cast<int>(p.keyframes.size());
    std::normal_distribution<double> noise(0.0, 1.0);
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.linear() = Eigen::AngleAxisd(0.05 * std::sin(k / 5.0), Eigen::Vector3d::UnitZ()).matrix();
    t.translation() = Eigen::Vector3d(0.5 * k, 0.3 * std::sin(k / 7.0), 0.5);
    truth.push_back(t);
    Keyframe kf;
    kf.id = k;
    kf.stamp = k;
    if (k > 0) {
      const Keyframe& prev = p.keyframes.back();
      Eigen::Isometry3d step = truth[k - 1].inverse() * t;
      step.translation() =
          1.02 * step.translation() + 0.005 * Eigen::Vector3d(noise(rng), noise(rng), 0);
      step.linear() =
          step.linear() * Eigen::AngleAxisd(0.002 * noise(rng), Eigen::Vector3d::UnitZ()).matrix();
      kf.previous = prev.id;
      kf.relative_odom = step;
      kf.odom_pose = prev.odom_pose * step;
      Eigen::Matrix<double, 6, 1> sigma;
      sigma << 0.01, 0.01, 0.005, 0.002, 0.002, 0.005;
      kf.odom_information = sigma.cwiseInverse().cwiseAbs2().asDiagonal();
      kf.pose = prev.pose * step;
    } else {
      kf.pose = kf.odom_pose = t;
    }
    p.keyframes.push_back(kf);
    for (int id : Seen(t)) {
      PlaneObservation o;
      o.keyframe = k;
      o.plane = id;
      o.local = Wall(id).Transformed(t.inverse());
      o.local.d += 0.005 * noise(rng);
      o.information = Eigen::Vector3d(1e6, 1e6, 1e4).asDiagonal();  // 1 mrad, 1 cm
      p.observations.push_back(o);
      if (id >= static_cast<int>(p.planes.size())) {
        Plane plane;
        plane.id = id;
        plane.plane = o.local.Transformed(kf.pose);
        p.planes.push_back(plane);
      }
    }
  }
};

BackendConfig Config(int window) {
  BackendConfig config;
  config.window_keyframes = window;
  config.window_plane_anchors = 10;
  config.max_iterations = 20;
  config.max_solver_time = 10.0;
  return config;
}

/// One windowed optimization of `graph` (the builder's way: the window's part is solved and
/// what moved is written back by id).
BackendSummary OptimizeWindowed(BackendProblem& graph, const BackendConfig& config) {
  BackendProblem p;
  p.planes = graph.planes;
  p.rooms = graph.rooms;
  p.floor = graph.floor;
  p.odometry_scale = graph.odometry_scale;
  SelectWindow(graph.keyframes, graph.observations, config, p);
  const BackendSummary summary = OptimizeSGraph(p, config);
  if (!summary.usable) return summary;
  for (const auto& k : p.keyframes)
    if (!p.constant_keyframes.count(k.id)) graph.keyframes[k.id].pose = k.pose;
  graph.planes = p.planes;
  graph.rooms = p.rooms;
  graph.odometry_scale = p.odometry_scale;
  return summary;
}

TEST(SGraphWindow, ProblemSizeStaysBoundedAsKeyframesGrow) {
  Corridor corridor;
  BackendProblem graph;
  const BackendConfig config = Config(30);
  std::vector<size_t> sizes;
  std::vector<int> residuals;
  for (int n = 1; n <= 400; ++n) {
    corridor.Append(graph);
    if (n % 100 != 0) continue;
    BackendProblem p;
    p.planes = graph.planes;
    SelectWindow(graph.keyframes, graph.observations, config, p);
    // The window, the keyframe before it, and at most window_plane_anchors per moved plane.
    EXPECT_LE(p.keyframes.size(), 30u + 1u + 10u * 4u) << n;
    EXPECT_GE(p.keyframes.size(), 31u) << n;
    EXPECT_EQ(p.keyframes.size() - p.constant_keyframes.size(), 30u) << n;
    EXPECT_EQ(p.keyframes.back().id, n - 1);
    sizes.push_back(p.keyframes.size());
    residuals.push_back(OptimizeWindowed(graph, config).num_residual_blocks);
  }
  // The same corridor ahead: the same problem at 200, 300 and 400 keyframes.
  EXPECT_EQ(sizes[1], sizes[3]);
  EXPECT_EQ(residuals[1], residuals[3]);
  EXPECT_LT(residuals[3], 400);  // the whole graph has over 1500 factors by then

  // No window, or a graph smaller than it: everything, nothing held.
  for (int window : {0, 500}) {
    BackendProblem p;
    SelectWindow(graph.keyframes, graph.observations, Config(window), p);
    EXPECT_EQ(p.keyframes.size(), graph.keyframes.size());
    EXPECT_EQ(p.observations.size(), graph.observations.size());
    EXPECT_TRUE(p.constant_keyframes.empty() && p.constant_planes.empty());
  }
}

TEST(SGraphWindow, RoomsAndFloorMoveOnlyWithAPlaneOfTheWindow) {
  Corridor corridor;
  BackendProblem graph;
  for (int n = 0; n < 60; ++n) corridor.Append(graph);  // up to x = 29.5 m
  BackendRoom old_room, new_room;
  old_room.id = 0;
  old_room.planes = {2, 3};  // cross walls at 5 and 10 m: seen by keyframes 0..19 only
  new_room.id = 1;
  new_room.planes = {3, 7};  // 10 m (old) and 30 m (seen by the window)
  graph.rooms = {old_room, new_room};
  graph.floor.present = true;
  BackendProblem p;
  p.rooms = graph.rooms;
  p.floor = graph.floor;
  SelectWindow(graph.keyframes, graph.observations, Config(20), p);
  EXPECT_EQ(p.constant_rooms, std::set<int>{0});
  EXPECT_EQ(p.constant_planes, std::set<int>{3});  // the moved room's plane the window misses
  EXPECT_FALSE(p.constant_floor);
  p.rooms = {old_room};
  SelectWindow(graph.keyframes, graph.observations, Config(20), p);
  EXPECT_TRUE(p.constant_floor);
}

TEST(SGraphWindow, OnlineWindowedSolutionMatchesTheWholeGraphs) {
  Corridor a, b;  // the same seed: the same walk and noise
  BackendProblem windowed, whole;
  const BackendConfig config = Config(40), no_window = Config(0);
  for (int n = 0; n < 160; ++n) {
    a.Append(windowed);
    b.Append(whole);
    ASSERT_TRUE(OptimizeWindowed(windowed, config).usable);
    ASSERT_TRUE(OptimizeSGraph(whole, no_window).usable);
  }
  double worst = 0.0, worst_truth = 0.0;
  for (size_t k = 0; k < whole.keyframes.size(); ++k) {
    const Eigen::Vector3d w = windowed.keyframes[k].pose.translation();
    worst = std::max(worst, (w - whole.keyframes[k].pose.translation()).head<2>().norm());
    worst_truth = std::max(worst_truth, (w - a.truth[k].translation()).head<2>().norm());
  }
  EXPECT_LT(worst, 0.01) << "windowed against whole, x-y, worst keyframe";
  EXPECT_LT(worst_truth, 0.03);
  const Eigen::Vector3d last = windowed.keyframes.back().pose.translation();
  EXPECT_LT((last - whole.keyframes.back().pose.translation()).head<2>().norm(), 0.01);
  EXPECT_NEAR(windowed.odometry_scale, whole.odometry_scale, 0.005);
}

TEST(SGraphWindow, ConfigValidatesTheWindow) {
  BackendConfig config;
  EXPECT_EQ(config.Validate(), "");
  config.window_keyframes = -1;
  EXPECT_NE(config.Validate().find("window_keyframes"), std::string::npos);
  config.window_keyframes = 1;
  EXPECT_NE(config.Validate().find("window_keyframes"), std::string::npos);
  config.window_keyframes = 0;
  EXPECT_EQ(config.Validate(), "");
  config.window_plane_anchors = 0;
  EXPECT_NE(config.Validate().find("window_plane_anchors"), std::string::npos);
  config = BackendConfig();
  config.window_cloud_voxel_size = -0.1;
  EXPECT_NE(config.Validate().find("window_cloud_voxel_size"), std::string::npos);
}

}  // namespace
}  // namespace sgraph
}  // namespace is_graphs
