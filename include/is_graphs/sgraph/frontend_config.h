#pragma once

#include <string>

#include "is_graphs/common/odometry_guard.h"
#include "is_graphs/sgraph/doorway_detection.h"
#include "is_graphs/sgraph/levels.h"

namespace is_graphs {
namespace sgraph {

/// Front end of the S-Graph: keyframes, filtering, plane extraction, association, rooms.
/// Lengths in metres, angles in degrees, times in seconds.
struct FrontendConfig {
  // Keyframes: a new one when the robot walked this far or turned this much since the last.
  double keyframe_distance{0.8};
  double keyframe_angle_deg{20.0};

  // Odometry: interpolation over gaps longer than this is refused (the scan is skipped);
  // a stamp this much earlier than the last one is a restart (the graph is reset).
  double max_odom_gap{0.5};
  double max_odom_extrapolation{0.15};
  double time_reset_threshold{1.0};
  // The node holds a cloud until odometry reaches its last firing, this long at most (its own
  // clock, s; 0: never waits): a cloud that arrives before the odometry of its own sweep would
  // be deskewed with the pose held over the sweep's end (ScanOdometrySync).
  double odom_wait{0.3};
  // What the odometry can do between two messages: NaN, glitches and lasting steps
  // (common::OdometryGuard; merger_node runs the same guard with the same values).
  common::OdometryGuardConfig odometry_guard;

  // Track loss (a kidnapped robot, an odometry jump): once the map holds track_loss_min_keyframes
  // keyframes, a keyframe that sees at least track_loss_min_walls wall segments of which at
  // least track_loss_new_share match no mapped plane restarts the S-Graph from that keyframe
  // (while tracking, even walking into a new room, the walls just left stay in view: at most a
  // third are new on the D bags). Off when detect_track_loss is false.
  bool detect_track_loss{true};
  int track_loss_min_keyframes{5};
  int track_loss_min_walls{5};
  double track_loss_new_share{0.8};
  double track_check_period{1.0};  // s: scans between keyframes are checked this often (0: never)

  // Filtering (ranges from the sensor; voxel edge of the extraction cloud and the map cloud).
  double min_range{0.6};
  double max_range{20.0};
  double voxel_size{0.08};
  double map_voxel_size{0.15};

  // Plane extraction: sequential RANSAC with a vertical (or horizontal) model.
  double plane_distance_threshold{0.05};
  double plane_max_angle_deg{5.0};  // deviation of a wall from vertical, the floor from level
  int ransac_iterations{150};
  int min_plane_points{60};
  int max_planes{24};
  double min_segment_length{0.6};  // horizontal extent of a wall segment
  double min_segment_height{0.3};  // vertical extent of a wall segment
  // m of a wall segment's length where its points rise min_segment_height or more (0.25 m
  // columns): one beam's arc on a far ceiling plus a post spans a wall's extent, not its surface.
  double min_segment_support{0.5};
  // A wall rises above the sensor: a segment whose top stays below the sensor + wall_min_rise
  // is furniture (a counter, a sofa, a pallet), unless the wall is so near that the highest
  // beam (sensor_max_elevation_deg) cannot see that high on it.
  double wall_min_rise{0.45};
  double sensor_max_elevation_deg{15.0};
  double segment_gap{0.5};  // coplanar points further apart are different segments
  // A wall's RANSAC inlier is kept only where the cloud around it (its cell of this size and the
  // 26 around it) faces the wall's way within wall_normal_max_angle_deg (90: no check).
  double wall_normal_cell{0.15};
  double wall_normal_max_angle_deg{30.0};
  double point_sigma{0.03};       // range noise used for the plane covariance
  int max_effective_points{150};  // cap on independent points (correlated errors)
  bool extract_floor{true};
  // A floor candidate is dropped when more than this share of its points have other points
  // straight above them (within floor_cover_height): walls, not a floor.
  double floor_max_covered{0.5};
  double floor_cover_height{0.6};

  // Association: Mahalanobis gate (chi-square, 3 dof) on the plane difference, with covariance
  // floors standing in for the pose uncertainty; plus an overlap test on the segments.
  double association_chi2{11.34};  // 99 %
  double association_min_sigma_d{0.08};
  double association_min_sigma_angle_deg{3.0};
  double association_max_gap{1.0};  // segment may start this far beyond the mapped extent
  // Two segments of one scan on one mapped plane must be this coplanar, else one is moved off
  // (a window set back in its wall, the two faces of a step).
  double association_coplanar_tolerance{0.05};
  // A keyframe's wall associated with a mapped plane but turned off the heading error its other
  // associated walls agree on is not used (scan_consistency.h): a door leaf swung a few degrees
  // off its wall. The tolerance grows with the path walked since the plane was last observed;
  // only planes observed by consistency_min_keyframes keyframes take part; 0 walls: no check.
  int consistency_min_walls{3};
  int consistency_min_keyframes{3};
  double consistency_angle_deg{1.5};
  double consistency_angle_deg_per_m{0.5};

  // A keyframe's slice (scan_slice.h): its points between slice_low and slice_high above
  // base_link (gravity-aligned; 0.9-2.1 m above the floor for a body 0.5 m up: above most
  // furniture, below ceilings), thinned to one per slice_cell square, at most slice_max_points.
  // The matcher's scan search (matching/scan_search.h) scores them against the BIM's walls.
  // Only the newest slice_keyframes keyframes carry theirs (0: none).
  double slice_low{0.4};
  double slice_high{1.6};
  double slice_cell{0.05};
  int slice_max_points{1500};
  int slice_keyframes{3};

  // Rooms and corridors.
  bool detect_rooms{true};
  double room_max_range{15.0};
  double room_min_width{1.2};
  double room_max_width{15.0};
  double corridor_max_width{3.0};
  double room_gap_margin{1.1};  // wall segments are extended this much (doorways)
  // m: a keyframe this close to a mapped wall's line (where the wall runs) stands in a doorway
  // or opening and sees two spaces at once: no room or corridor is detected there (0: off).
  double room_opening_band{0.35};
  int room_rays{180};
  // Share of the rays that two opposed pairs of walls must take (ending on them within the
  // rectangle they bound) for a four-wall room; the rest go through doorways. Else a
  // polygonal room of all the walls hit.
  double room_rectangle_share{0.7};
  double room_max_opening{2.0};  // m: the widest unwalled stretch of a four-wall room's side

  // Doorways where the walked path crosses wall planes (ROS parameters doorway_<field>).
  DoorwayConfig doorways;
  // Storeys walked: a keyframe's level from its height (ROS parameters level_<field>).
  LevelConfig levels;

  /// Empty when valid, else what is wrong (naming the field).
  std::string Validate() const;
};

}  // namespace sgraph
}  // namespace is_graphs
