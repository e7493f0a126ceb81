#include "is_graphs/merging/merger_config.h"

#include <cmath>
#include <sstream>
#include <utility>

namespace is_graphs {
namespace merging {

std::string MergerConfig::Validate() const {
  const std::pair<const char*, double> positive[] = {
      {"surface_angle_sigma_deg", surface_angle_sigma_deg},
      {"surface_offset_sigma", surface_offset_sigma},
      {"room_sigma", room_sigma},
      {"match_huber", match_huber},
      {"wall_deviation_offset_sigma", wall_deviation_offset_sigma},
      {"wall_deviation_angle_sigma_deg", wall_deviation_angle_sigma_deg},
      {"wall_turn_release_deg", wall_turn_release_deg},
      {"prior_translation_sigma", prior_translation_sigma},
      {"prior_yaw_sigma_deg", prior_yaw_sigma_deg},
      {"max_solver_time", max_solver_time},
      {"gate_angle_deg", gate_angle_deg},
      {"gate_offset", gate_offset},
      {"gate_room", gate_room},
      {"max_chi2_per_dof", max_chi2_per_dof},
      {"max_jump_translation", max_jump_translation},
      {"max_jump_yaw_deg", max_jump_yaw_deg},
      {"pose_sigma_xy", pose_sigma_xy},
      {"pose_sigma_z", pose_sigma_z},
      {"pose_sigma_roll_pitch_deg", pose_sigma_roll_pitch_deg},
      {"pose_sigma_yaw_deg", pose_sigma_yaw_deg},
      {"recent_min_length", recent_min_length}};
  for (const auto& [name, value] : positive) {
    if (!std::isfinite(value) || value <= 0.0) {
      std::ostringstream out;
      out << name << " must be a positive number, got " << value;
      return out.str();
    }
  }
  if (!std::isfinite(min_inlier_fraction) || min_inlier_fraction < 0.0 ||
      min_inlier_fraction > 1.0) {
    return "min_inlier_fraction must be in [0, 1], got " + std::to_string(min_inlier_fraction);
  }
  if (!std::isfinite(recent_min_support) || recent_min_support < 0.0 || recent_min_support > 1.0)
    return "recent_min_support must be in [0, 1], got " + std::to_string(recent_min_support);
  if (recent_keyframes < 0) return "recent_keyframes must be >= 0 (0: off)";
  if (recent_min_planes < 1) return "recent_min_planes must be >= 1";
  if (min_surface_inliers < 0)
    return "min_surface_inliers must be >= 0, got " + std::to_string(min_surface_inliers);
  if (min_room_inliers < 0)
    return "min_room_inliers must be >= 0, got " + std::to_string(min_room_inliers);
  if (min_surface_inliers_without_rooms < 0)
    return "min_surface_inliers_without_rooms must be >= 0, got " +
           std::to_string(min_surface_inliers_without_rooms);
  if (max_iterations < 1)
    return "max_iterations must be >= 1, got " + std::to_string(max_iterations);
  if (!(function_tolerance > 0.0 && function_tolerance < 1.0))
    return "function_tolerance must be in (0, 1), got " + std::to_string(function_tolerance);
  if (window_keyframes < 0)
    return "window_keyframes must be >= 0 (0: all keyframes), got " +
           std::to_string(window_keyframes);
  if (num_threads < 1) return "num_threads must be >= 1, got " + std::to_string(num_threads);
  // The Cauchy prior's steepest slope, 1 / (2σ), must be below the most one matched plane pulls
  // with (its Huber: 1 / surface_offset_sigma), or a wall built off the plan can never leave it.
  if (estimate_wall_deviations && wall_deviation_offset_sigma <= 0.5 * surface_offset_sigma) {
    std::ostringstream out;
    out << "wall_deviation_offset_sigma must exceed surface_offset_sigma / 2 ("
        << wall_deviation_offset_sigma << " <= " << 0.5 * surface_offset_sigma
        << "): no wall could leave the plan; set estimate_wall_deviations false to hold them";
    return out.str();
  }
  std::string error = sgraph.Validate();
  if (!error.empty()) return "sgraph." + error;
  error = agraph.Validate();
  if (!error.empty()) return "agraph." + error;
  return "";
}

}  // namespace merging
}  // namespace is_graphs
