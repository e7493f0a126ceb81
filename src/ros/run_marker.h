#pragma once
// A file a node keeps up to date while it runs, under $ROS_HOME/is_graphs/ (ROS's default
// ~/.ros): a node that starts and finds its own marker from the same ROS run (the master's
// /run_id) was restarted (respawned after a crash or a kill) and knows what its predecessor held.
#include <string>

namespace is_graphs {
namespace ros_run {

class RunMarker {
 public:
  /// `name`: the node's resolved name (e.g. /sgraph_node); `run_id`: the master's /run_id.
  RunMarker(const std::string& name, const std::string& run_id);

  /// What a previous process of this node wrote in this ROS run, or "" (none, another run's).
  std::string Previous() const { return previous_; }
  /// Records `summary` (atomically: a temporary file renamed); a failure is returned, not thrown.
  std::string Write(const std::string& summary) const;
  const std::string& path() const { return path_; }

 private:
  std::string path_, run_id_, previous_;
};

}  // namespace ros_run
}  // namespace is_graphs
