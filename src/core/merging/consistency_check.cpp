#include "is_graphs/merging/consistency_check.h"

#include <Eigen/Geometry>
#include <cmath>
#include <sstream>

#include "is_graphs/geometry/se3.h"

namespace is_graphs {
namespace merging {

ConsistencyReport CheckConsistency(const MergeSolution& solution, const MergerConfig& config,
                                   bool starting) {
  ConsistencyReport report;
  double chi2 = 0.0;
  int dof = 0;
  for (const auto& s : solution.surfaces) {
    ++report.surface_pairs;
    if (s.used && s.angle_deg <= config.gate_angle_deg && s.offset <= config.gate_offset) {
      ++report.surface_inliers;
      chi2 += s.chi2;
      dof += s.dof;
    } else {
      report.outlier_surfaces.push_back(s.s_id);
    }
  }
  for (const auto& r : solution.rooms) {
    ++report.room_pairs;
    if (r.distance <= config.gate_room) {
      ++report.room_inliers;
      chi2 += r.chi2;
      dof += r.dof;
    } else {
      report.outlier_rooms.push_back(r.s_id);
    }
  }
  const int pairs = report.surface_pairs + report.room_pairs;
  const int inliers = report.surface_inliers + report.room_inliers;
  report.inlier_fraction = pairs > 0 ? static_cast<double>(inliers) / pairs : 0.0;
  report.chi2_per_dof = dof > 0 ? chi2 / dof : 0.0;
  std::ostringstream out;
  out.precision(3);
  out << "surfaces " << report.surface_inliers << "/" << report.surface_pairs << ", rooms "
      << report.room_inliers << "/" << report.room_pairs << " inliers, chi2/dof "
      << report.chi2_per_dof;
  std::string why;
  if (!solution.usable)
    why = "the solve failed (" + solution.message + ")";
  else if (report.surface_inliers < config.min_surface_inliers)
    why = "too few surface inliers";
  else if (starting && report.room_pairs > 0 && report.room_inliers < config.min_room_inliers)
    why = "too few room inliers";
  else if (starting && report.room_pairs == 0 &&
           report.surface_inliers < config.min_surface_inliers_without_rooms)
    why = "too few surface inliers for a match without rooms";
  else if (report.inlier_fraction < config.min_inlier_fraction)
    why = "too many outlier pairs";
  else if (report.chi2_per_dof > config.max_chi2_per_dof)
    why = "inlier residuals too large";
  report.consistent = why.empty();
  report.message = why.empty() ? out.str() : why + ": " + out.str();
  return report;
}

TransformJump CompareTransforms(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                const Eigen::Vector2d& point_in_map) {
  const Eigen::Vector2d pa = Eigen::Rotation2Dd(a.z()) * point_in_map + a.head<2>();
  const Eigen::Vector2d pb = Eigen::Rotation2Dd(b.z()) * point_in_map + b.head<2>();
  TransformJump jump;
  jump.translation = (pa - pb).norm();
  jump.yaw_deg = std::abs(geometry::NormalizeAngle(a.z() - b.z())) * 180.0 / M_PI;
  return jump;
}

bool TransformsAgree(const TransformJump& jump, const MergerConfig& config) {
  return jump.translation <= config.max_jump_translation && jump.yaw_deg <= config.max_jump_yaw_deg;
}

}  // namespace merging
}  // namespace is_graphs
