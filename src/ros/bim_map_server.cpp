#include "bim_map_server.h"

#include <tf2/LinearMath/Quaternion.h>

#include "is_graphs/agraph/agraph_queries.h"
#include "param_helpers.h"

namespace is_graphs {
namespace ros_nav {

nav_msgs::OccupancyGrid ToMsg(const navigation::OccupancyGrid& grid, const std::string& frame_id) {
  nav_msgs::OccupancyGrid msg;
  msg.header.frame_id = frame_id;
  msg.header.stamp = ros::Time::now();
  msg.info.map_load_time = msg.header.stamp;
  msg.info.resolution = static_cast<float>(grid.resolution);
  msg.info.width = grid.width;
  msg.info.height = grid.height;
  msg.info.origin.position.x = grid.origin.x();
  msg.info.origin.position.y = grid.origin.y();
  msg.info.origin.position.z = grid.elevation;
  msg.info.origin.orientation.w = 1.0;
  msg.data.assign(grid.cells.begin(), grid.cells.end());
  return msg;
}

geometry_msgs::PoseStamped ToPoseMsg(const navigation::Place& place, const std::string& frame_id) {
  geometry_msgs::PoseStamped msg;
  msg.header.frame_id = frame_id;
  msg.header.stamp = ros::Time::now();
  msg.pose.position.x = place.position.x();
  msg.pose.position.y = place.position.y();
  msg.pose.position.z = place.position.z();
  tf2::Quaternion q;
  q.setRPY(0.0, 0.0, place.yaw);
  msg.pose.orientation.x = q.x();
  msg.pose.orientation.y = q.y();
  msg.pose.orientation.z = q.z();
  msg.pose.orientation.w = q.w();
  return msg;
}

std::vector<merging::WallDeviation> FromMsg(const is_graphs::WallDeviations& msg) {
  std::vector<merging::WallDeviation> out;
  for (const auto& w : msg.walls) {
    merging::WallDeviation d;
    d.wall_id = w.wall_id;
    d.guid = w.guid;
    d.name = w.name;
    d.status = static_cast<merging::WallStatus>(w.status);
    d.offset = w.offset;
    d.angle = w.angle;
    d.start = Eigen::Vector2d(w.start.x, w.start.y);
    d.end = Eigen::Vector2d(w.end.x, w.end.y);
    out.push_back(d);
  }
  return out;
}

BimMapServer::BimMapServer(ros::NodeHandle& nh, const agraph::AGraph& graph,
                           const geometry::TriangleMesh* mesh, const BimMapParams& params)
    : graph_(graph), mesh_(mesh), params_(params), places_(graph, params.places) {
  int first = -1;
  for (size_t s = 0; s < graph.storeys.size(); ++s) {
    auto one = agraph::SelectStorey(graph, static_cast<int>(s));
    storey_graphs_.push_back(one.ok() ? std::move(one).value() : agraph::AGraph{});
    auto grid = navigation::BuildStoreyGrid(storey_graphs_.back(), mesh, params.grid);
    if (!grid.ok()) {
      ROS_WARN("agraph_node: no bim_map for storey '%s': %s", graph.storeys[s].name.c_str(),
               grid.error().c_str());
      grids_.emplace_back();
      continue;
    }
    grids_.emplace_back(std::move(grid).value());
    const Eigen::Vector2i snapped = places_.SnapToFree(static_cast<int>(s), *grids_.back(), graph);
    if (snapped[1] > 0)
      ROS_WARN("agraph_node: storey '%s': %d locate goals have no free cell near them",
               graph.storeys[s].name.c_str(), snapped[1]);
    if (first < 0 || graph.storeys[s].elevation < graph.storeys[first].elevation) first = s;
  }
  if (!params.storey.empty()) {
    const auto found = agraph::FindStorey(graph, params.storey);
    if (!found.ok()) throw ros_params::ParamError("parameter '~map_storey': " + found.error());
    first = found.value();
  }
  map_pub_ = nh.advertise<nav_msgs::OccupancyGrid>("bim_map", 1, /*latch=*/true);
  as_built_pub_ = nh.advertise<nav_msgs::OccupancyGrid>("bim_map/as_built", 1, /*latch=*/true);
  if (first >= 0) Publish(first);
  match_sub_ = nh.subscribe("graph_match", 1, &BimMapServer::OnGraphMatch, this);
  deviations_sub_ = nh.subscribe("deviations", 1, &BimMapServer::OnDeviations, this);
  locate_srv_ = nh.advertiseService("locate", &BimMapServer::OnLocate, this);
}

void BimMapServer::Publish(int storey) {
  storey_ = storey;
  if (!grids_[storey]) {
    ROS_WARN("agraph_node: storey '%s' has no map: bim_map unchanged",
             graph_.storeys[storey].name.c_str());
    return;
  }
  const auto msg = ToMsg(*grids_[storey], params_.frame_id);
  map_pub_.publish(msg);
  as_built_pub_.publish(msg);  // as planned until the storey's deviations arrive
  as_built_cells_ = grids_[storey]->cells;
  ROS_INFO("agraph_node: bim_map: storey '%s', %u x %u cells of %.3f m",
           graph_.storeys[storey].name.c_str(), msg.info.width, msg.info.height,
           msg.info.resolution);
}

void BimMapServer::OnGraphMatch(const is_graphs::GraphMatch::ConstPtr& msg) {
  if (msg->status != is_graphs::GraphMatch::UNIQUE || msg->storey_id < 0 ||
      msg->storey_id >= static_cast<int>(grids_.size()) || msg->storey_id == storey_ ||
      msg->a_graph_sha256 != graph_.source.sha256)
    return;
  Publish(msg->storey_id);
}

void BimMapServer::OnDeviations(const is_graphs::WallDeviations::ConstPtr& msg) {
  if (storey_ < 0 || !grids_[storey_] || msg->a_graph_sha256 != graph_.source.sha256) return;
  const auto deviations = FromMsg(*msg);
  auto grid =
      navigation::BuildStoreyGrid(storey_graphs_[storey_], mesh_, params_.grid, &deviations);
  if (!grid.ok()) {
    ROS_WARN_THROTTLE(10.0, "agraph_node: bim_map/as_built: %s", grid.error().c_str());
    return;
  }
  if (grid.value().cells == as_built_cells_) return;  // unchanged: no new 100s of kB
  as_built_cells_ = grid.value().cells;
  as_built_pub_.publish(ToMsg(grid.value(), params_.frame_id));
}

bool BimMapServer::OnLocate(is_graphs::Locate::Request& req, is_graphs::Locate::Response& res) {
  const auto found = places_.Locate(req.name, req.storey);
  if (!found.ok()) {
    res.success = false;
    res.message = found.error();
    return true;
  }
  for (const auto& p : found.value()) {
    res.matches.push_back(ToPoseMsg(p, params_.frame_id));
    res.match_storeys.push_back(p.storey_name);
    res.match_kinds.push_back(navigation::ToString(p.kind));
    res.match_names.push_back(p.name.empty() ? p.guid : p.name);
    // A storey without a map has no free cell either.
    res.match_free.push_back(p.on_free_cell && p.storey >= 0 &&
                             p.storey < static_cast<int>(grids_.size()) && grids_[p.storey]);
  }
  res.success = found.value().size() == 1;
  if (res.success) {
    res.pose = res.matches[0];
    res.storey_name = res.match_storeys[0];
    res.kind = res.match_kinds[0];
    res.free = res.match_free[0];
    res.message = res.kind + " '" + res.match_names[0] + "' on storey '" + res.storey_name + "'";
    if (!res.free)
      res.message +=
          ": no free cell of the storey's bim_map within 1.5 m of it (not a goal to "
          "plan to)";
  } else {
    res.message = "'" + req.name + "' is ambiguous: " + std::to_string(res.matches.size()) +
                  " matches (matches, match_storeys); give the storey or a GlobalId";
  }
  return true;
}

}  // namespace ros_nav
}  // namespace is_graphs
