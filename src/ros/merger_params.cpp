#include "merger_params.h"

#include <utility>

#include "param_helpers.h"

namespace is_graphs {
namespace ros_merger {

using ros_params::Read;

MergerNodeParams ReadParams(const ros::NodeHandle& pnh) {
  MergerNodeParams p;
  auto& c = p.merger;
  Read(pnh, "surface_angle_sigma_deg", c.surface_angle_sigma_deg);
  Read(pnh, "surface_offset_sigma", c.surface_offset_sigma);
  Read(pnh, "room_sigma", c.room_sigma);
  Read(pnh, "match_huber", c.match_huber);
  Read(pnh, "estimate_wall_deviations", c.estimate_wall_deviations);
  Read(pnh, "wall_deviation_offset_sigma", c.wall_deviation_offset_sigma);
  Read(pnh, "wall_deviation_angle_sigma_deg", c.wall_deviation_angle_sigma_deg);
  Read(pnh, "wall_turn_release_deg", c.wall_turn_release_deg);
  Read(pnh, "prior_translation_sigma", c.prior_translation_sigma);
  Read(pnh, "prior_yaw_sigma_deg", c.prior_yaw_sigma_deg);
  Read(pnh, "optimize_sgraph", c.optimize_sgraph);
  Read(pnh, "window_keyframes", c.window_keyframes);
  Read(pnh, "calibrate_odometry", c.calibrate_odometry);
  Read(pnh, "max_iterations", c.max_iterations);
  Read(pnh, "max_solver_time", c.max_solver_time);
  Read(pnh, "function_tolerance", c.function_tolerance);
  Read(pnh, "num_threads", c.num_threads);
  Read(pnh, "gate_angle_deg", c.gate_angle_deg);
  Read(pnh, "gate_offset", c.gate_offset);
  Read(pnh, "gate_room", c.gate_room);
  Read(pnh, "min_inlier_fraction", c.min_inlier_fraction);
  Read(pnh, "min_surface_inliers", c.min_surface_inliers);
  Read(pnh, "min_room_inliers", c.min_room_inliers);
  Read(pnh, "min_surface_inliers_without_rooms", c.min_surface_inliers_without_rooms);
  Read(pnh, "max_chi2_per_dof", c.max_chi2_per_dof);
  Read(pnh, "max_jump_translation", c.max_jump_translation);
  Read(pnh, "recent_keyframes", c.recent_keyframes);
  Read(pnh, "recent_min_length", c.recent_min_length);
  Read(pnh, "recent_min_planes", c.recent_min_planes);
  Read(pnh, "recent_min_support", c.recent_min_support);
  Read(pnh, "max_jump_yaw_deg", c.max_jump_yaw_deg);
  Read(pnh, "pose_sigma_xy", c.pose_sigma_xy);
  Read(pnh, "pose_sigma_z", c.pose_sigma_z);
  Read(pnh, "pose_sigma_roll_pitch_deg", c.pose_sigma_roll_pitch_deg);
  Read(pnh, "pose_sigma_yaw_deg", c.pose_sigma_yaw_deg);
  Read(pnh, "bim_frame", p.bim_frame);
  Read(pnh, "map_frame", p.map_frame);
  Read(pnh, "odom_frame", p.odom_frame);
  Read(pnh, "match_wait", p.match_wait);
  Read(pnh, "status_rate", p.status_rate);
  Read(pnh, "marker_s_graph_lift", p.markers.s_graph_lift);
  Read(pnh, "watchdog_rate", p.watchdog_rate);
  Read(pnh, "carry_over_restart", p.carry_over_restart);
  Read(pnh, "carry_max_distance", p.carry_max_distance);
  auto& w = p.watchdog;
  Read(pnh, "degraded_after", w.degraded_after);
  Read(pnh, "lost_after", w.lost_after);
  Read(pnh, "max_distance_without_sgraph", w.max_distance_without_sgraph);
  Read(pnh, "lost_distance_without_sgraph", w.lost_distance_without_sgraph);
  Read(pnh, "degraded_sigma_per_m", w.degraded_sigma_per_m);
  Read(pnh, "degraded_yaw_sigma_deg_per_m", w.degraded_yaw_sigma_deg_per_m);
  if (const std::string e = w.Validate(); !e.empty())
    throw ros_params::ParamError("parameter '" + pnh.resolveName(e.substr(0, e.find(' '))) + "'" +
                                 e.substr(e.find(' ')));
  ros_params::ReadOdometryGuard(pnh, p.odometry_guard);
  p.markers.frame_id = p.bim_frame;
  for (const auto& [name, value] :
       {std::pair<const char*, const std::string*>{"bim_frame", &p.bim_frame},
        {"map_frame", &p.map_frame},
        {"odom_frame", &p.odom_frame}})
    if (value->empty())
      throw ros_params::ParamError("parameter '" + pnh.resolveName(name) + "' must not be empty");
  for (const auto& [name, value] : {std::pair<const char*, double>{"match_wait", p.match_wait},
                                    {"status_rate", p.status_rate},
                                    {"watchdog_rate", p.watchdog_rate},
                                    {"carry_max_distance", p.carry_max_distance}})
    if (!(value > 0.0))
      throw ros_params::ParamError("parameter '" + pnh.resolveName(name) + "' must be > 0");
  const std::string error = c.Validate();
  if (!error.empty())  // Validate names the field first, which is the parameter's name
    throw ros_params::ParamError("parameter '" + pnh.resolveName(error.substr(0, error.find(' '))) +
                                 "': " + error);
  return p;
}

}  // namespace ros_merger
}  // namespace is_graphs
