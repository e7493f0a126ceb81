// The `deviations` topic (deviation_node on the whole pipeline, issue 21) against a scenario's
// known deviations, given as params by the .test: every wall reported MOVED is in `moved` (name:
// offset m) or `rotated` (name: deg) within the tolerances, every wall there is MOVED (or NOT_SEEN
// when `allow_not_seen`), NOT_BUILT exactly for `not_built`, at least `min_extra` EXTRA walls
// and at most `max_extra`, every other wall AS_PLANNED or NOT_SEEN, each wall with its GUID.
// And the merge's own wall states (is_graph's wall_states): every wall in `moved` at least
// `state_min_offset` off has a state within `state_tolerance` of its offset, and every state of
// a wall on the plan is within `state_plan_tolerance` of it. (The states are shrunk toward the
// plan by their prior: a moved wall's state must be on its side, at least `state_min_share` of
// the way, and at most `state_tolerance` beyond.) Doors (the message's doorways): CLOSED exactly
// for `closed_doors` (names), at least `min_present_doors` PRESENT.
#include <geometry_msgs/PoseStamped.h>
#include <gtest/gtest.h>
#include <is_graphs/ISGraph.h>
#include <is_graphs/WallDeviations.h>
#include <ros/ros.h>

#include <cmath>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <vector>

namespace {

std::mutex mutex_;
is_graphs::WallDeviations::ConstPtr last_;
is_graphs::ISGraph::ConstPtr last_is_graph_;
int received_ = 0;
ros::WallTime last_truth_;
bool truth_seen_ = false;

// The merge's as-built states (is_graph.wall_states) against the scenario's moves.
void CheckWallStates(const std::map<std::string, double>& moved,
                     const std::map<std::string, double>& rotated,
                     const std::set<std::string>& not_built) {
  ros::NodeHandle pnh("~");
  const double min_offset = pnh.param("state_min_offset", 0.15);
  const double tolerance = pnh.param("state_tolerance", 0.03);
  const double min_share = pnh.param("state_min_share", 0.5);
  const double plan_tolerance = pnh.param("state_plan_tolerance", 0.02);
  const int min_checked = pnh.param("state_min_checked", 0);
  ASSERT_TRUE(last_is_graph_) << "no message on is_graph";
  std::map<int, std::string> names;
  for (const auto& w : last_is_graph_->a_graph.walls) names[w.id] = w.name;
  std::set<std::string> with_state;
  for (const auto& w : last_is_graph_->wall_states) {
    const std::string& name = names[w.wall_id];
    with_state.insert(name);
    std::printf("  merge state %-10s offset %+.3f m (sigma %.3f) angle %+.2f deg, %d pairs\n",
                name.c_str(), w.offset, w.offset_sigma, w.angle * 180 / M_PI, w.pairs);
    if (moved.count(name) || rotated.count(name) || not_built.count(name)) continue;
    EXPECT_NEAR(w.offset, 0.0, plan_tolerance) << name << " is on the plan";
  }
  EXPECT_FALSE(last_is_graph_->wall_states.empty());
  int checked = 0;
  for (const auto& [name, offset] : moved) {
    if (std::abs(offset) < min_offset || !with_state.count(name)) continue;
    ++checked;
    for (const auto& w : last_is_graph_->wall_states) {
      if (names[w.wall_id] == name) {
        const double along = w.offset * (offset > 0 ? 1.0 : -1.0);  // toward the truth
        EXPECT_GE(along, min_share * std::abs(offset)) << name << " state " << w.offset;
        EXPECT_LE(along, std::abs(offset) + tolerance) << name << " state " << w.offset;
      }
    }
  }
  EXPECT_GE(checked, min_checked) << "moved walls with a merge state";
}

// The doors and openings: CLOSED exactly for `closed_doors`, at least `min_present_doors` PRESENT.
void CheckDoors(const is_graphs::WallDeviations& m) {
  ros::NodeHandle pnh("~");
  std::vector<std::string> closed_list;
  pnh.getParam("closed_doors", closed_list);
  const std::set<std::string> closed(closed_list.begin(), closed_list.end());
  const int min_present = pnh.param("min_present_doors", 0);
  int present = 0;
  std::set<std::string> reported_closed;
  for (const auto& d : m.doorways) {
    std::printf("  door %-8s %-24s status %u walked %d rays %d blocked %d\n", d.name.c_str(),
                d.guid.c_str(), d.status, d.walked_through, d.rays_through, d.blocked_views);
    present += d.status == is_graphs::DoorwayDeviation::PRESENT;
    if (d.status == is_graphs::DoorwayDeviation::CLOSED) reported_closed.insert(d.name);
  }
  EXPECT_EQ(reported_closed, closed) << "the doors reported CLOSED";
  EXPECT_GE(present, min_present) << "doors PRESENT";
}

TEST(DeviationsTest, MatchTheScenariosKnownDeviations) {
  ros::NodeHandle nh, pnh("~");
  std::map<std::string, double> moved, rotated;
  std::vector<std::string> not_built_list;
  pnh.getParam("moved", moved);
  pnh.getParam("rotated", rotated);
  pnh.getParam("not_built", not_built_list);
  const std::set<std::string> not_built(not_built_list.begin(), not_built_list.end());
  const double offset_tol = pnh.param("offset_tolerance", 0.015);
  const double angle_tol = pnh.param("angle_tolerance_deg", 0.5);
  const bool allow_not_seen = pnh.param("allow_not_seen", false);
  const int min_extra = pnh.param("min_extra", 0), max_extra = pnh.param("max_extra", 0);
  const double max_wait = pnh.param("max_wait", 150.0);

  ros::Subscriber s = nh.subscribe<is_graphs::WallDeviations>(
      "deviations", 10,
      boost::function<void(const is_graphs::WallDeviations::ConstPtr&)>(
          [](const is_graphs::WallDeviations::ConstPtr& m) {
            std::lock_guard<std::mutex> lock(mutex_);
            last_ = m;
            ++received_;
          }));
  ros::Subscriber g =
      nh.subscribe<is_graphs::ISGraph>("is_graph", 10,
                                       boost::function<void(const is_graphs::ISGraph::ConstPtr&)>(
                                           [](const is_graphs::ISGraph::ConstPtr& m) {
                                             std::lock_guard<std::mutex> lock(mutex_);
                                             last_is_graph_ = m;
                                           }));
  ros::Subscriber t = nh.subscribe<geometry_msgs::PoseStamped>(
      "ground_truth/pose", 100,
      boost::function<void(const geometry_msgs::PoseStamped::ConstPtr&)>(
          [](const geometry_msgs::PoseStamped::ConstPtr&) {
            std::lock_guard<std::mutex> lock(mutex_);
            last_truth_ = ros::WallTime::now();
            truth_seen_ = true;
          }));
  const ros::WallTime start = ros::WallTime::now();
  while (ros::ok() && (ros::WallTime::now() - start).toSec() < max_wait) {
    ros::WallDuration(0.2).sleep();
    std::lock_guard<std::mutex> lock(mutex_);
    if (truth_seen_ && (ros::WallTime::now() - last_truth_).toSec() > 4.0) break;  // bag over
  }
  std::lock_guard<std::mutex> lock(mutex_);
  ASSERT_TRUE(last_) << "no message on deviations in " << max_wait << " s";
  std::printf("deviations: %d messages, the last from S-Graph revision %u\n", received_,
              last_->s_graph_revision);
  int extra = 0, seen = 0;
  for (const auto& w : last_->walls) {
    std::printf("  %-10s %-24s status %u offset %+.3f m angle %+.2f deg\n", w.name.c_str(),
                w.guid.c_str(), w.status, w.offset, w.angle * 180 / M_PI);
    if (w.status == is_graphs::WallDeviation::EXTRA) {
      ++extra;
      continue;
    }
    EXPECT_FALSE(w.guid.empty()) << w.name;
    seen += w.status != is_graphs::WallDeviation::NOT_SEEN;
    const bool unseen_ok = allow_not_seen && w.status == is_graphs::WallDeviation::NOT_SEEN;
    if (not_built.count(w.name)) {
      EXPECT_TRUE(w.status == is_graphs::WallDeviation::NOT_BUILT || unseen_ok) << w.name;
      continue;
    }
    EXPECT_NE(w.status, is_graphs::WallDeviation::NOT_BUILT) << w.name << " was built";
    const double offset = moved.count(w.name) ? moved[w.name] : 0.0;
    const double angle = rotated.count(w.name) ? rotated[w.name] : 0.0;
    if (moved.count(w.name) || rotated.count(w.name)) {
      if (unseen_ok) continue;
      EXPECT_EQ(w.status, is_graphs::WallDeviation::MOVED) << w.name;
      EXPECT_NEAR(w.offset, offset, offset_tol) << w.name;
      EXPECT_NEAR(w.angle * 180 / M_PI, angle, angle_tol) << w.name;
    } else {
      EXPECT_TRUE(w.status == is_graphs::WallDeviation::AS_PLANNED ||
                  w.status == is_graphs::WallDeviation::NOT_SEEN)
          << w.name << " is on the plan, reported status " << int(w.status) << " offset "
          << w.offset;
    }
  }
  EXPECT_GE(extra, min_extra);
  EXPECT_LE(extra, max_extra);
  EXPECT_GT(seen, 0);
  CheckDoors(*last_);
  CheckWallStates(moved, rotated, not_built);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_deviations");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
