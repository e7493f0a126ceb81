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
// for `closed_doors` (names), at least `min_present_doors` PRESENT. And agraph_node's navigation
// maps fed by this deviation_node: `bim_map/as_built` frees each wall reported NOT_BUILT that
// `bim_map` (the plan) blocks, blocks each wall reported MOVED on its side (and frees its planned
// line where it moved more than its half thickness and two cells), and blocks each EXTRA wall.
#include <geometry_msgs/PoseStamped.h>
#include <gtest/gtest.h>
#include <is_graphs/ISGraph.h>
#include <is_graphs/WallDeviations.h>
#include <nav_msgs/OccupancyGrid.h>
#include <ros/ros.h>

#include <algorithm>
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
// Each wall's newest merge state over the run, with the is_graph message it came in (a wall
// seen early leaves the merge's keyframe window and the later messages: its state is still the
// merge's estimate of it).
std::map<int, std::pair<is_graphs::WallDeviationState, int>> latest_states_;
int is_graphs_received_ = 0;
int received_ = 0;
ros::WallTime last_truth_;
bool truth_seen_ = false;
nav_msgs::OccupancyGrid::ConstPtr plan_map_, as_built_map_;

// Occupied (>= 50) within one cell of (x, y) in bim; false outside the grid.
bool OccupiedNear(const nav_msgs::OccupancyGrid& g, double x, double y) {
  const double r = g.info.resolution;
  const int ci = static_cast<int>(std::floor((x - g.info.origin.position.x) / r));
  const int cj = static_cast<int>(std::floor((y - g.info.origin.position.y) / r));
  for (int j = cj - 1; j <= cj + 1; ++j)
    for (int i = ci - 1; i <= ci + 1; ++i)
      if (i >= 0 && j >= 0 && i < static_cast<int>(g.info.width) &&
          j < static_cast<int>(g.info.height) && g.data[j * g.info.width + i] >= 50)
        return true;
  return false;
}

// Share of the points (every half cell) along the middle 60 % of a wall's mid-line, moved by
// `shift` along its left normal, that are occupied within one cell.
double OccupiedShare(const nav_msgs::OccupancyGrid& g, const geometry_msgs::Point& a,
                     const geometry_msgs::Point& b, double shift) {
  const double dx = b.x - a.x, dy = b.y - a.y, length = std::hypot(dx, dy);
  if (!(length > 0.0)) return 0.0;
  const double nx = -dy / length, ny = dx / length;
  const int n = std::max(2, static_cast<int>(0.6 * length / (0.5 * g.info.resolution)));
  int occupied = 0;
  for (int k = 0; k < n; ++k) {
    const double t = 0.2 + 0.6 * k / (n - 1);
    occupied += OccupiedNear(g, a.x + t * dx + shift * nx, a.y + t * dy + shift * ny);
  }
  return static_cast<double>(occupied) / n;
}

// The maps against the deviations reported (see the file's comment).
void CheckAsBuiltMap(const is_graphs::WallDeviations& m) {
  ASSERT_TRUE(plan_map_) << "no message on bim_map (agraph_node)";
  ASSERT_TRUE(as_built_map_) << "no message on bim_map/as_built (agraph_node)";
  EXPECT_EQ(as_built_map_->header.frame_id, plan_map_->header.frame_id);
  std::map<std::string, double> thickness;
  if (last_is_graph_)
    for (const auto& w : last_is_graph_->a_graph.walls) thickness[w.name] = w.thickness;
  const double cell = plan_map_->info.resolution;
  int checked = 0;
  for (const auto& w : m.walls) {
    const double plan = OccupiedShare(*plan_map_, w.start, w.end, 0.0);
    const double built = OccupiedShare(*as_built_map_, w.start, w.end, 0.0);
    if (w.status == is_graphs::WallDeviation::NOT_BUILT) {
      std::printf("  as-built map: %s NOT_BUILT: blocked %.2f in the plan, %.2f as built\n",
                  w.name.c_str(), plan, built);
      EXPECT_GE(plan, 0.8) << w.name << ": the plan's map does not block it";
      EXPECT_LE(built, 0.1) << w.name << " NOT_BUILT is still blocked in bim_map/as_built";
      ++checked;
    } else if (w.status == is_graphs::WallDeviation::EXTRA) {
      std::printf("  as-built map: EXTRA wall: blocked %.2f in the plan, %.2f as built\n", plan,
                  built);
      EXPECT_GE(built, 0.8) << "an EXTRA wall is not blocked in bim_map/as_built";
      ++checked;
    } else if (w.status == is_graphs::WallDeviation::MOVED && std::abs(w.offset) >= 2 * cell &&
               std::abs(w.angle) < 0.01 && thickness.count(w.name)) {
      // The offset's side (the first surface's normal) is not in the message: the moved line is
      // blocked on one of the two sides.
      const double side = std::max(OccupiedShare(*as_built_map_, w.start, w.end, w.offset),
                                   OccupiedShare(*as_built_map_, w.start, w.end, -w.offset));
      const bool clears = std::abs(w.offset) - thickness[w.name] / 2 >= 2 * cell;
      std::printf(
          "  as-built map: %s MOVED %+.3f m: planned line blocked %.2f in the plan, "
          "%.2f as built; moved line blocked %.2f\n",
          w.name.c_str(), w.offset, plan, built, side);
      EXPECT_GE(side, 0.8) << w.name << ": its moved line is not blocked as built";
      if (clears) {
        EXPECT_LE(built, 0.1) << w.name << ": its planned line is still blocked";
      }
      ++checked;
    }
  }
  std::printf("  as-built map: %d walls checked\n", checked);
}

// The merge's as-built states (is_graph.wall_states, each wall's newest) against the scenario's
// moves.
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
  for (const auto& [id, latest] : latest_states_) {
    const auto& [w, message] = latest;
    const std::string& name = names[id];
    with_state.insert(name);
    std::printf(
        "  merge state %-10s offset %+.3f m (sigma %.3f) angle %+.2f deg, %d pairs (is_graph %d "
        "of %d)\n",
        name.c_str(), w.offset, w.offset_sigma, w.angle * 180 / M_PI, w.pairs, message,
        is_graphs_received_);
    if (moved.count(name) || rotated.count(name) || not_built.count(name)) continue;
    EXPECT_NEAR(w.offset, 0.0, plan_tolerance) << name << " is on the plan";
  }
  EXPECT_FALSE(last_is_graph_->wall_states.empty());
  int checked = 0;
  for (const auto& [name, offset] : moved) {
    if (std::abs(offset) < min_offset || !with_state.count(name)) continue;
    ++checked;
    for (const auto& [id, latest] : latest_states_) {
      const auto& w = latest.first;
      if (names[id] == name) {
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
                                             ++is_graphs_received_;
                                             for (const auto& w : m->wall_states)
                                               latest_states_[w.wall_id] = {w, is_graphs_received_};
                                           }));
  ros::Subscriber t = nh.subscribe<geometry_msgs::PoseStamped>(
      "ground_truth/pose", 100,
      boost::function<void(const geometry_msgs::PoseStamped::ConstPtr&)>(
          [](const geometry_msgs::PoseStamped::ConstPtr&) {
            std::lock_guard<std::mutex> lock(mutex_);
            last_truth_ = ros::WallTime::now();
            truth_seen_ = true;
          }));
  const auto latest = [](nav_msgs::OccupancyGrid::ConstPtr* into) {
    return boost::function<void(const nav_msgs::OccupancyGrid::ConstPtr&)>(
        [into](const nav_msgs::OccupancyGrid::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex_);
          *into = m;
        });
  };
  ros::Subscriber plan_sub =
      nh.subscribe<nav_msgs::OccupancyGrid>("bim_map", 1, latest(&plan_map_));
  ros::Subscriber built_sub =
      nh.subscribe<nav_msgs::OccupancyGrid>("bim_map/as_built", 1, latest(&as_built_map_));
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
  CheckAsBuiltMap(*last_);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_deviations");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
