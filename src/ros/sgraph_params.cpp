#include "sgraph_params.h"

#include <utility>

#include "param_helpers.h"

namespace is_graphs {
namespace ros_sgraph {

SGraphNodeParams ReadParams(const ros::NodeHandle& pnh) {
  using ros_params::Read;
  SGraphNodeParams p;
  Read(pnh, "map_frame", p.map_frame);
  Read(pnh, "odom_frame", p.odom_frame);
  Read(pnh, "base_frame", p.base_frame);
  Read(pnh, "map_cloud_period", p.map_cloud_period);
  Read(pnh, "map_cloud_voxel", p.map_cloud_voxel);
  Read(pnh, "tf_rate", p.tf_rate);
  Read(pnh, "cloud_queue", p.cloud_queue);
  Read(pnh, "input_timeout", p.input_timeout);
  Read(pnh, "max_cloud_lag", p.max_cloud_lag);
  if (p.cloud_queue < 1)
    throw ros_params::ParamError("parameter '" + pnh.resolveName("cloud_queue") + "' must be >= 1");
  for (const auto& [name, value] :
       {std::pair<const char*, double>{"input_timeout", p.input_timeout},
        {"max_cloud_lag", p.max_cloud_lag}})
    if (!(value > 0.0))
      throw ros_params::ParamError("parameter '" + pnh.resolveName(name) + "' must be > 0");
  Read(pnh, "marker_layer_spacing", p.markers.layer_spacing);
  std::string layout = ros_conversions::ToString(p.cloud.layout);
  Read(pnh, "cloud_layout", layout);
  const auto kind = ros_conversions::ParseCloudLayoutKind(layout);
  if (!kind)
    throw ros_params::ParamError("parameter '" + pnh.resolveName("cloud_layout") +
                                 "' must be one of " + ros_conversions::CloudLayoutChoices() +
                                 ", got '" + layout + "'");
  p.cloud.layout = *kind;
  Read(pnh, "cloud_max_sweep_period", p.cloud.max_sweep_period);
  for (const auto* name : {"map_frame", "odom_frame", "base_frame"}) {
    std::string v;
    if (pnh.getParam(name, v) && v.empty())
      throw ros_params::ParamError("parameter '" + pnh.resolveName(name) + "' must not be empty");
  }
  if (!(p.map_cloud_period > 0.0))
    throw ros_params::ParamError("parameter '" + pnh.resolveName("map_cloud_period") +
                                 "' must be > 0");
  if (!(p.map_cloud_voxel > 0.0))
    throw ros_params::ParamError("parameter '" + pnh.resolveName("map_cloud_voxel") +
                                 "' must be > 0");
  if (!(p.tf_rate > 0.0))
    throw ros_params::ParamError("parameter '" + pnh.resolveName("tf_rate") + "' must be > 0");
  auto& f = p.frontend;
  Read(pnh, "keyframe_distance", f.keyframe_distance);
  Read(pnh, "keyframe_angle_deg", f.keyframe_angle_deg);
  Read(pnh, "max_odom_gap", f.max_odom_gap);
  Read(pnh, "max_odom_extrapolation", f.max_odom_extrapolation);
  Read(pnh, "odom_wait", f.odom_wait);
  Read(pnh, "time_reset_threshold", f.time_reset_threshold);
  f.odometry_guard.time_reset_threshold = f.time_reset_threshold;
  ros_params::ReadOdometryGuard(pnh, f.odometry_guard);
  Read(pnh, "min_range", f.min_range);
  Read(pnh, "max_range", f.max_range);
  Read(pnh, "voxel_size", f.voxel_size);
  Read(pnh, "map_voxel_size", f.map_voxel_size);
  Read(pnh, "plane_distance_threshold", f.plane_distance_threshold);
  Read(pnh, "plane_max_angle_deg", f.plane_max_angle_deg);
  Read(pnh, "ransac_iterations", f.ransac_iterations);
  Read(pnh, "min_plane_points", f.min_plane_points);
  Read(pnh, "max_planes", f.max_planes);
  Read(pnh, "min_segment_length", f.min_segment_length);
  Read(pnh, "min_segment_height", f.min_segment_height);
  Read(pnh, "min_segment_support", f.min_segment_support);
  Read(pnh, "wall_min_rise", f.wall_min_rise);
  Read(pnh, "sensor_max_elevation_deg", f.sensor_max_elevation_deg);
  Read(pnh, "segment_gap", f.segment_gap);
  Read(pnh, "wall_normal_cell", f.wall_normal_cell);
  Read(pnh, "wall_normal_max_angle_deg", f.wall_normal_max_angle_deg);
  Read(pnh, "point_sigma", f.point_sigma);
  Read(pnh, "max_effective_points", f.max_effective_points);
  Read(pnh, "extract_floor", f.extract_floor);
  Read(pnh, "floor_max_covered", f.floor_max_covered);
  Read(pnh, "floor_cover_height", f.floor_cover_height);
  Read(pnh, "association_chi2", f.association_chi2);
  Read(pnh, "association_min_sigma_d", f.association_min_sigma_d);
  Read(pnh, "association_min_sigma_angle_deg", f.association_min_sigma_angle_deg);
  Read(pnh, "association_max_gap", f.association_max_gap);
  Read(pnh, "association_coplanar_tolerance", f.association_coplanar_tolerance);
  Read(pnh, "consistency_min_walls", f.consistency_min_walls);
  Read(pnh, "consistency_min_keyframes", f.consistency_min_keyframes);
  Read(pnh, "slice_low", f.slice_low);
  Read(pnh, "slice_high", f.slice_high);
  Read(pnh, "slice_cell", f.slice_cell);
  Read(pnh, "slice_max_points", f.slice_max_points);
  Read(pnh, "slice_keyframes", f.slice_keyframes);
  Read(pnh, "consistency_angle_deg", f.consistency_angle_deg);
  Read(pnh, "consistency_angle_deg_per_m", f.consistency_angle_deg_per_m);
  Read(pnh, "detect_rooms", f.detect_rooms);
  Read(pnh, "detect_track_loss", f.detect_track_loss);
  Read(pnh, "track_loss_min_keyframes", f.track_loss_min_keyframes);
  Read(pnh, "track_loss_min_walls", f.track_loss_min_walls);
  Read(pnh, "track_loss_new_share", f.track_loss_new_share);
  Read(pnh, "track_check_period", f.track_check_period);
  Read(pnh, "room_max_range", f.room_max_range);
  Read(pnh, "room_min_width", f.room_min_width);
  Read(pnh, "room_max_width", f.room_max_width);
  Read(pnh, "corridor_max_width", f.corridor_max_width);
  Read(pnh, "room_gap_margin", f.room_gap_margin);
  Read(pnh, "room_opening_band", f.room_opening_band);
  Read(pnh, "room_rays", f.room_rays);
  Read(pnh, "room_rectangle_share", f.room_rectangle_share);
  Read(pnh, "room_max_opening", f.room_max_opening);
  Read(pnh, "level_tolerance", f.levels.tolerance);
  Read(pnh, "level_min_rise", f.levels.min_rise);
  Read(pnh, "level_settle", f.levels.settle);
  Read(pnh, "level_landing_length", f.levels.landing_length);
  Read(pnh, "doorway_detect", f.doorways.detect);
  Read(pnh, "doorway_max_step", f.doorways.max_step);
  Read(pnh, "doorway_min_wall_height", f.doorways.min_wall_height);
  Read(pnh, "doorway_extent_margin", f.doorways.extent_margin);
  Read(pnh, "doorway_max_width", f.doorways.max_width);
  Read(pnh, "doorway_merge_distance", f.doorways.merge_distance);
  Read(pnh, "doorway_wall_band", f.doorways.wall_band);
  Read(pnh, "doorway_band_low", f.doorways.band_low);
  Read(pnh, "doorway_band_high", f.doorways.band_high);
  auto& b = p.backend;
  Read(pnh, "max_iterations", b.max_iterations);
  Read(pnh, "max_solver_time", b.max_solver_time);
  Read(pnh, "num_threads", b.num_threads);
  Read(pnh, "odom_sigma_translation", b.odom_sigma_translation);
  Read(pnh, "odom_sigma_rotation", b.odom_sigma_rotation);
  Read(pnh, "odom_sigma_z", b.odom_sigma_z);
  Read(pnh, "odom_sigma_roll_pitch", b.odom_sigma_roll_pitch);
  Read(pnh, "odometry_scale_sigma", b.odometry_scale_sigma);
  Read(pnh, "odometry_scale_max_error", b.odometry_scale_max_error);
  Read(pnh, "plane_huber", b.plane_huber);
  Read(pnh, "room_cauchy", b.room_cauchy);
  Read(pnh, "room_sigma", b.room_sigma);
  Read(pnh, "corridor_along_sigma", b.corridor_along_sigma);
  Read(pnh, "floor_sigma", b.floor_sigma);
  Read(pnh, "polygon_room_sigma", b.polygon_room_sigma);
  Read(pnh, "window_keyframes", b.window_keyframes);
  Read(pnh, "window_plane_anchors", b.window_plane_anchors);
  Read(pnh, "window_cloud_voxel_size", b.window_cloud_voxel_size);
  // The configs name the field; the parameter carries the same name under the node.
  const std::string ns = pnh.getNamespace() + "/";
  for (const std::string& e : {p.cloud.Validate(), f.Validate(), b.Validate()}) {
    if (e.empty()) continue;
    const size_t space = e.find(' ');  // "<field> <what>"
    throw ros_params::ParamError("parameter '" + ns + e.substr(0, space) + "'" +
                                 (space == std::string::npos ? "" : e.substr(space)));
  }
  p.markers.frame_id = p.map_frame;
  return p;
}

}  // namespace ros_sgraph
}  // namespace is_graphs
