#pragma once
// agraph_node's navigation side (docs/navigation.md): the storey the robot is on as a latched
// nav_msgs/OccupancyGrid `bim_map` (switched on graph_match's storey), its as-built version
// `bim_map/as_built` (the `deviations` topic applied), and the `locate` service (places as goals).

#include <is_graphs/GraphMatch.h>
#include <is_graphs/Locate.h>
#include <is_graphs/WallDeviations.h>
#include <nav_msgs/OccupancyGrid.h>
#include <ros/ros.h>

#include <optional>
#include <string>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/navigation/occupancy_grid.h"
#include "is_graphs/navigation/places.h"

namespace is_graphs {
namespace ros_nav {

struct BimMapParams {
  navigation::GridConfig grid;
  navigation::PlaceConfig places;
  std::string storey;  // the storey shown first (name or index); "" the lowest with a map
  std::string frame_id{"bim"};
};

nav_msgs::OccupancyGrid ToMsg(const navigation::OccupancyGrid& grid, const std::string& frame_id);
geometry_msgs::PoseStamped ToPoseMsg(const navigation::Place& place, const std::string& frame_id);
std::vector<merging::WallDeviation> FromMsg(const is_graphs::WallDeviations& msg);

class BimMapServer {
 public:
  /// Builds every storey's grid and the places of `graph` (the A-Graph agraph_node publishes;
  /// `mesh` may be null). Throws ros_params::ParamError for a `~map_storey` that is no storey.
  BimMapServer(ros::NodeHandle& nh, const agraph::AGraph& graph, const geometry::TriangleMesh* mesh,
               const BimMapParams& params);

  int storey() const { return storey_; }

 private:
  void Publish(int storey);
  void OnGraphMatch(const is_graphs::GraphMatch::ConstPtr& msg);
  void OnDeviations(const is_graphs::WallDeviations::ConstPtr& msg);
  bool OnLocate(is_graphs::Locate::Request& req, is_graphs::Locate::Response& res);

  const agraph::AGraph& graph_;
  const geometry::TriangleMesh* mesh_;
  BimMapParams params_;
  std::vector<agraph::AGraph> storey_graphs_;
  std::vector<std::optional<navigation::OccupancyGrid>> grids_;  // per storey; none: no map
  navigation::PlaceIndex places_;
  int storey_{-1};
  std::vector<std::int8_t> as_built_cells_;  // as last published
  ros::Publisher map_pub_, as_built_pub_;
  ros::Subscriber match_sub_, deviations_sub_;
  ros::ServiceServer locate_srv_;
};

}  // namespace ros_nav
}  // namespace is_graphs
