#include <sstream>

#include "is_graphs/sgraph/backend_config.h"
#include "is_graphs/sgraph/doorway_detection.h"
#include "is_graphs/sgraph/frontend_config.h"

namespace is_graphs {
namespace sgraph {
namespace {

// Appends "name must be ... (got v)" when the check fails; returns the first failure only.
class Checker {
 public:
  void Positive(const char* name, double v) {
    if (error_.empty() && !(v > 0.0)) Fail(name, "must be > 0", v);
  }
  void NonNegative(const char* name, double v) {
    if (error_.empty() && !(v >= 0.0)) Fail(name, "must be >= 0", v);
  }
  void Range(const char* name, double v, double lo, double hi) {
    if (error_.empty() && !(v >= lo && v <= hi)) {
      std::ostringstream s;
      s << "must be in [" << lo << ", " << hi << "]";
      Fail(name, s.str(), v);
    }
  }
  void Less(const char* a, double va, const char* b, double vb) {
    if (error_.empty() && !(va < vb)) {
      std::ostringstream s;
      s << a << " (" << va << ") must be less than " << b << " (" << vb << ")";
      error_ = s.str();
    }
  }
  std::string error() const { return error_; }

 private:
  void Fail(const char* name, const std::string& what, double v) {
    std::ostringstream s;
    s << name << " " << what << " (got " << v << ")";
    error_ = s.str();
  }
  std::string error_;
};

}  // namespace

std::string FrontendConfig::Validate() const {
  Checker c;
  c.Positive("keyframe_distance", keyframe_distance);
  c.Range("keyframe_angle_deg", keyframe_angle_deg, 1e-3, 180.0);
  c.Positive("max_odom_gap", max_odom_gap);
  c.NonNegative("max_odom_extrapolation", max_odom_extrapolation);
  c.Positive("time_reset_threshold", time_reset_threshold);
  c.Range("odom_wait", odom_wait, 0.0, 10.0);
  c.Range("track_loss_min_keyframes", track_loss_min_keyframes, 1, 1e6);
  c.Range("track_loss_min_walls", track_loss_min_walls, 1, 1000);
  c.Range("track_loss_new_share", track_loss_new_share, 0.5, 1.0);
  c.NonNegative("track_check_period", track_check_period);
  c.NonNegative("min_range", min_range);
  c.Less("min_range", min_range, "max_range", max_range);
  c.Range("voxel_size", voxel_size, 0.005, 1.0);
  c.Range("map_voxel_size", map_voxel_size, 0.005, 5.0);
  c.Range("plane_distance_threshold", plane_distance_threshold, 1e-3, 1.0);
  c.Range("plane_max_angle_deg", plane_max_angle_deg, 0.1, 45.0);
  c.Range("ransac_iterations", ransac_iterations, 1, 1e5);
  c.Range("min_plane_points", min_plane_points, 3, 1e7);
  c.Range("max_planes", max_planes, 1, 1000);
  c.Positive("min_segment_length", min_segment_length);
  c.NonNegative("min_segment_height", min_segment_height);
  c.NonNegative("min_segment_support", min_segment_support);
  c.NonNegative("wall_min_rise", wall_min_rise);
  c.Range("sensor_max_elevation_deg", sensor_max_elevation_deg, 0.0, 89.0);
  c.Positive("segment_gap", segment_gap);
  c.Range("wall_normal_cell", wall_normal_cell, 0.01, 5.0);
  c.Range("wall_normal_max_angle_deg", wall_normal_max_angle_deg, 1.0, 90.0);
  c.Positive("point_sigma", point_sigma);
  c.Range("max_effective_points", max_effective_points, 3, 1e7);
  c.Range("floor_max_covered", floor_max_covered, 0.0, 1.0);
  c.Positive("floor_cover_height", floor_cover_height);
  c.Positive("association_chi2", association_chi2);
  c.Positive("association_min_sigma_d", association_min_sigma_d);
  c.Positive("association_min_sigma_angle_deg", association_min_sigma_angle_deg);
  c.NonNegative("association_max_gap", association_max_gap);
  c.Positive("association_coplanar_tolerance", association_coplanar_tolerance);
  c.NonNegative("consistency_min_walls", consistency_min_walls);
  c.NonNegative("consistency_min_keyframes", consistency_min_keyframes);
  c.Positive("consistency_angle_deg", consistency_angle_deg);
  c.NonNegative("consistency_angle_deg_per_m", consistency_angle_deg_per_m);
  c.Less("slice_low", slice_low, "slice_high", slice_high);
  c.Range("slice_cell", slice_cell, 0.005, 1.0);
  c.Range("slice_max_points", slice_max_points, 1, 1e6);
  c.Range("slice_keyframes", slice_keyframes, 0, 1000);
  c.Positive("room_max_range", room_max_range);
  c.Positive("room_min_width", room_min_width);
  c.Less("room_min_width", room_min_width, "room_max_width", room_max_width);
  c.Positive("corridor_max_width", corridor_max_width);
  c.NonNegative("room_gap_margin", room_gap_margin);
  c.NonNegative("room_opening_band", room_opening_band);
  c.Range("room_rays", room_rays, 16, 3600);
  c.Range("room_rectangle_share", room_rectangle_share, 0.5, 1.0);
  c.Positive("room_max_opening", room_max_opening);
  if (!c.error().empty()) return c.error();
  if (const std::string e = doorways.Validate(); !e.empty()) return e;
  if (const std::string e = odometry_guard.Validate(); !e.empty()) return e;
  return levels.Validate();
}

std::string DoorwayConfig::Validate() const {
  Checker c;
  c.Positive("doorway_max_step", max_step);
  c.NonNegative("doorway_min_wall_height", min_wall_height);
  c.NonNegative("doorway_extent_margin", extent_margin);
  c.Positive("doorway_max_width", max_width);
  c.Positive("doorway_merge_distance", merge_distance);
  c.Positive("doorway_wall_band", wall_band);
  c.Less("doorway_band_low", band_low, "doorway_band_high", band_high);
  return c.error();
}

std::string BackendConfig::Validate() const {
  Checker c;
  c.Range("max_iterations", max_iterations, 1, 1000);
  c.Positive("max_solver_time", max_solver_time);
  c.Range("num_threads", num_threads, 1, 64);
  c.Positive("odom_sigma_translation", odom_sigma_translation);
  c.Positive("odom_sigma_rotation", odom_sigma_rotation);
  c.Positive("odom_sigma_z", odom_sigma_z);
  c.Positive("odom_sigma_roll_pitch", odom_sigma_roll_pitch);
  c.NonNegative("odometry_scale_sigma", odometry_scale_sigma);
  c.Range("odometry_scale_max_error", odometry_scale_max_error, 1e-3, 0.9);
  c.Positive("plane_huber", plane_huber);
  c.Positive("room_cauchy", room_cauchy);
  c.Positive("room_sigma", room_sigma);
  c.Positive("corridor_along_sigma", corridor_along_sigma);
  c.Positive("floor_sigma", floor_sigma);
  c.Positive("polygon_room_sigma", polygon_room_sigma);
  c.Range("window_keyframes", window_keyframes, 0, 1e6);
  if (window_keyframes > 0) c.Range("window_keyframes", window_keyframes, 2, 1e6);
  c.Range("window_plane_anchors", window_plane_anchors, 1, 1e6);
  c.Range("window_cloud_voxel_size", window_cloud_voxel_size, 0.0, 5.0);
  return c.error();
}

}  // namespace sgraph
}  // namespace is_graphs
