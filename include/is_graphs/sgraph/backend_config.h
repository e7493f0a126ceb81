#pragma once

#include <string>

namespace is_graphs {
namespace sgraph {

/// Back end: the Ceres problem over keyframes, planes, rooms, corridors and the floor.
struct BackendConfig {
  int max_iterations{6};         // warm-started from the last solution: a few suffice
  double max_solver_time{0.08};  // s: the budget of one optimization (the next one resumes)
  int num_threads{1};

  // Odometry edge standard deviations (per metre walked + a floor), in m and rad.
  double odom_sigma_translation{0.02};
  double odom_sigma_rotation{0.005};
  double odom_sigma_z{0.005};  // z, roll, pitch are near-true on a legged robot
  double odom_sigma_roll_pitch{0.002};
  // The odometry's distance scale factor s (legged odometry over- or under-reads distance by a
  // few per cent, more on some floors): estimated with the graph under a prior N(1, σ²), kept
  // within 1 ± odometry_scale_max_error. σ = 0 holds s at 1 (odometry taken as it reads).
  double odometry_scale_sigma{0.05};
  double odometry_scale_max_error{0.2};

  // Robust losses (on the whitened residual).
  double plane_huber{1.0};
  double room_cauchy{1.0};

  // Structure factors: standard deviation of a room / corridor wall about its measured offset,
  // of a corridor centre along its axis, and of a room about the floor centre.
  double room_sigma{0.1};
  double corridor_along_sigma{2.0};
  double floor_sigma{0.5};
  // How well a room's published centre stands for the room's true centre (the information on it
  // in s_graph, which the merge reads): a four-wall room's centre is where its mid-lines meet
  // (room_sigma); a polygonal room's is the centroid of the part seen, pulled towards a doorway
  // or a crossing corridor that opens the view.
  double polygon_room_sigma{1.0};

  // Windowed optimization (issue 22, hour-long runs): each optimization moves only the newest
  // window_keyframes keyframes and what they observe (planes, the rooms on those planes, the
  // floor); older keyframes enter held at their values where they tie something that moves (the
  // keyframe before the window through its odometry edge; of the others observing a moved plane,
  // the newest window_plane_anchors per plane), the rest of the graph stays out. 0: the whole
  // graph every time. Once a keyframe leaves the window its cloud (read only by the doorway
  // width, cached before, and the map cloud) is thinned to window_cloud_voxel_size (0: kept).
  int window_keyframes{100};
  int window_plane_anchors{20};
  double window_cloud_voxel_size{0.15};  // m

  /// Empty when valid, else what is wrong (naming the field).
  std::string Validate() const;
};

}  // namespace sgraph
}  // namespace is_graphs
