#include "is_graphs/matching/matcher_config.h"

#include <cmath>
#include <sstream>

namespace is_graphs {
namespace matching {
namespace {

// "" when lo < value <= hi (lo_open) or lo <= value <= hi, else a message naming `name`.
std::string Check(const char* name, double value, double lo, double hi, bool lo_open) {
  const bool ok = std::isfinite(value) && (lo_open ? value > lo : value >= lo) && value <= hi;
  if (ok) return "";
  std::ostringstream out;
  out << name << " must be in " << (lo_open ? "(" : "[") << lo << ", " << hi << "] (got " << value
      << ")";
  return out.str();
}

}  // namespace

std::string MatcherConfig::Validate() const {
  const struct {
    const char* name;
    double value, lo, hi;
    bool lo_open;
  } fields[] = {
      {"angle_tolerance_deg", angle_tolerance_deg, 0.0, 45.0, true},
      {"offset_tolerance", offset_tolerance, 0.0, 5.0, true},
      {"centre_tolerance", centre_tolerance, 0.0, 10.0, true},
      {"min_plane_fraction", min_plane_fraction, 0.0, 1.0, true},
      {"yaw_tolerance_deg", yaw_tolerance_deg, 0.0, 45.0, true},
      {"lever_arm_slack", lever_arm_slack, 0.0, 1.0, false},
      {"quality_sigma", quality_sigma, 0.0, 5.0, true},
      {"corridor_weight", corridor_weight, 0.0, 1.0, true},
      {"wall_crossing_penalty", wall_crossing_penalty, 0.0, 100.0, false},
      {"door_margin", door_margin, 0.0, 5.0, false},
      {"max_path_step", max_path_step, 0.0, 100.0, true},
      {"surface_evidence_weight", surface_evidence_weight, 0.0, 10.0, false},
      {"surface_full_length", surface_full_length, 0.0, 100.0, true},
      {"surface_min_length", surface_min_length, 0.0, 100.0, false},
      {"surface_min_height", surface_min_height, 0.0, 100.0, false},
      {"outside_penalty", outside_penalty, 0.0, 10.0, false},
      {"outside_margin", outside_margin, 0.0, 100.0, false},
      {"doorway_evidence_weight", doorway_evidence_weight, 0.0, 10.0, false},
      {"doorway_tolerance", doorway_tolerance, 0.0, 5.0, true},
      {"doorway_width_tolerance", doorway_width_tolerance, 0.0, 5.0, true},
      {"sight_penalty", sight_penalty, 0.0, 10.0, false},
      {"unique_min_wall_share", unique_min_wall_share, 0.0, 1.0, false},
      {"unique_min_walls", unique_min_walls, 0.0, 1e6, false},
      {"sight_viewpoints", static_cast<double>(sight_viewpoints), 1.0, 100.0, false},
      {"sight_door_margin", sight_door_margin, 0.0, 5.0, false},
      {"proposal_corner_reach", proposal_corner_reach, 0.0, 5.0, true},
      {"proposal_min_walls", proposal_min_walls, 1.0, 1e6, false},
      {"proposal_min_share", proposal_min_share, 0.0, 1.0, true},
      {"proposal_margin", proposal_margin, 0.0, 1e6, true},
      {"proposal_margin_share", proposal_margin_share, 0.0, 1.0, false},
      {"proposal_crossing_penalty", proposal_crossing_penalty, 0.0, 1e6, false},
      {"proposal_max_candidates", static_cast<double>(proposal_max_candidates), 1.0, 1e9, false},
      {"ambiguity_margin", ambiguity_margin, 0.0, 100.0, false},
      {"doubt_centre_tolerance", doubt_centre_tolerance, 0.0, 10.0, false},
      {"cluster_yaw_deg", cluster_yaw_deg, 0.0, 90.0, true},
      {"cluster_translation", cluster_translation, 0.0, 100.0, true},
      {"min_matched_rooms", static_cast<double>(min_matched_rooms), 1.0, 1e6, false},
      {"min_matched_fraction", min_matched_fraction, 0.0, 1.0, false},
      {"max_seeds", static_cast<double>(max_seeds), 1.0, 1e9, false},
      {"deviation_offset", deviation_offset, 0.0, 5.0, true},
      {"deviation_angle_deg", deviation_angle_deg, 0.0, 45.0, true},
      {"deviation_max_offset", deviation_max_offset, 0.0, 5.0, true},
      {"deviation_max_angle_deg", deviation_max_angle_deg, 0.0, 45.0, true},
      {"stair_height_tolerance", stair_height_tolerance, 0.0, 100.0, true},
      {"storey_level_tolerance", storey_level_tolerance, 0.0, 1e6, true},
      {"storey_level_tolerance_per_m", storey_level_tolerance_per_m, 0.0, 1.0, false},
      {"proposal_cross_check_max_rooms", static_cast<double>(proposal_cross_check_max_rooms), 1.0,
       1e6, false},
  };
  for (const auto& f : fields) {
    const std::string error = Check(f.name, f.value, f.lo, f.hi, f.lo_open);
    if (!error.empty()) return error;
  }
  return scan_search.Validate();
}

}  // namespace matching
}  // namespace is_graphs
