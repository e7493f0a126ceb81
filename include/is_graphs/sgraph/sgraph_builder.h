#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "is_graphs/common/odometry_guard.h"
#include "is_graphs/sgraph/backend_config.h"
#include "is_graphs/sgraph/doorway_detection.h"
#include "is_graphs/sgraph/frontend_config.h"
#include "is_graphs/sgraph/keyframe_selector.h"
#include "is_graphs/sgraph/odometry_buffer.h"
#include "is_graphs/sgraph/plane_association.h"
#include "is_graphs/sgraph/plane_extraction.h"
#include "is_graphs/sgraph/point_types.h"
#include "is_graphs/sgraph/sgraph.h"
#include "is_graphs/sgraph/sgraph_backend.h"

namespace is_graphs {
namespace sgraph {

/// The S-Graph, built online: the facade the node and the benchmark call.
///
///   builder.AddOdometry(t, odom_T_base);        // every odometry message
///   auto r = builder.AddScan(scan, base_T_sensor);  // every cloud: keyframe or not
///   builder.Optimize();                         // on a worker thread, after new keyframes
///   SGraph g = builder.Snapshot();              // what the node publishes
///
/// Thread safety: all methods may be called concurrently. Optimize() holds the graph's lock
/// only to copy the problem and to write the result back, never while Ceres solves, so scans
/// are not blocked by the optimizer; keyframes added meanwhile are moved by the correction.
class SGraphBuilder {
 public:
  enum class ScanStatus { kSkipped, kNotKeyframe, kKeyframe };
  struct ScanResult {
    ScanStatus status{ScanStatus::kSkipped};
    std::string warning;  // set when the scan was skipped or something was off
    int keyframe{-1};     // the new keyframe's id
    int num_segments{0};  // planes seen in the keyframe
    int num_new_planes{0};
    int num_walls{0};      // of the planes seen, the vertical ones
    int num_new_walls{0};  // ... that matched no mapped plane
    // Walls matched to a mapped plane that the keyframe's other walls contradict (a door leaf
    // swung off its wall, a person before it): not used (scan_consistency.h).
    int num_contradicted{0};
    // Track lost (most walls seen match nothing mapped: a kidnapped robot, an odometry jump):
    // the S-Graph was dropped and restarted from this keyframe (see FrontendConfig).
    bool restarted{false};
    // Stage times of a keyframe scan [ms] (the benchmark's per-stage latency).
    double preprocess_ms{0.0};   // deskew, range and voxel filters
    double extraction_ms{0.0};   // floor and wall plane extraction
    double association_ms{0.0};  // plane association and mapping
    double rooms_ms{0.0};        // room, corridor and floor detection
  };
  struct OdometryResult {
    bool accepted{true};
    bool reset{false};  // time went backwards: the graph was reset
    std::string warning;
    common::OdometryGuard::Verdict verdict{common::OdometryGuard::Verdict::kAccepted};
    // The reading as the graph uses it (the guard's correction applied), when accepted.
    Eigen::Isometry3d odom_T_base{Eigen::Isometry3d::Identity()};
  };

  SGraphBuilder(const FrontendConfig& frontend, const BackendConfig& backend);

  OdometryResult AddOdometry(double stamp, const Eigen::Isometry3d& odom_T_base);
  ScanResult AddScan(const Scan& scan, const Eigen::Isometry3d& base_T_sensor);
  BackendSummary Optimize();
  /// Drops the whole graph (a restarted bag, a new run).
  void Reset();

  SGraph Snapshot() const;
  /// map <- odom, from the latest keyframe's optimized and odometry poses.
  /// map <- odom: the frame of the odometry readings as they come (tf map -> odom).
  Eigen::Isometry3d MapToOdom() const;
  /// Messages the odometry guard skipped and lasting steps it bridged, since the start.
  int odometry_rejected() const;
  int odometry_bridged() const;
  /// The keyframes' clouds in M at their current poses, voxel-filtered.
  PointList MapCloud(double voxel_size) const;
  int num_keyframes() const;
  /// Points kept in the keyframes' clouds (their memory; old ones thinned, BackendConfig).
  size_t num_cloud_points() const;
  /// The stamp of the newest odometry accepted (-1 before any, and after a reset).
  double last_odometry_stamp() const;
  /// Keyframes added since the last Optimize() started.
  int pending_keyframes() const;

 private:
  struct MapPlane {
    Plane plane;
    Eigen::Vector3d start{Eigen::Vector3d::Zero()};
    Eigen::Vector3d end{Eigen::Vector3d::Zero()};
    bool horizontal{false};
    Eigen::Matrix3d information{Eigen::Matrix3d::Zero()};  // fused, tangent at the normal
    int merged_into{-1};    // >= 0: a duplicate of that plane, merged into it (the id stays unused)
    int last_keyframe{-1};  // the newest keyframe that observed it
    int num_keyframes{0};   // keyframes that observed it
  };

  void ResetLocked();
  /// Drops the graph but keeps the odometry and the stamps (a restart after a track loss).
  void ClearGraphLocked();
  /// Appends a keyframe at odom_pose with its cloud, associates its segments, finds rooms.
  void AppendKeyframeLocked(double stamp, const Eigen::Isometry3d& odom_pose, PointList cloud,
                            std::vector<Eigen::Vector3f> slice,
                            const std::vector<PlaneSegment>& segments, ScanResult& result);
  // Track loss (sgraph_builder_track.cpp).
  bool TrackLost(const ScanResult& result) const;
  bool TrackCheckDueLocked(double stamp) const;
  /// Counts in result the walls among `segments` and those that match no mapped plane.
  void CountWallsLocked(const Eigen::Isometry3d& pose, const std::vector<PlaneSegment>& segments,
                        ScanResult& result) const;
  /// Drops the graph and starts it again from a keyframe of this scan (result: its warning).
  void RestartLocked(double stamp, const Eigen::Isometry3d& odom_pose, PointList cloud,
                     std::vector<Eigen::Vector3f> slice,
                     const std::vector<PlaneSegment>& segments, ScanResult& result);
  std::vector<MapPlaneView> MapViewsLocked() const;
  static std::vector<PlaneSegment> InMap(const std::vector<PlaneSegment>& segments,
                                         const Eigen::Isometry3d& pose);
  // Association and map update for one keyframe's segments (in base_link); mutex held.
  void AddPlaneObservations(int keyframe, const std::vector<PlaneSegment>& segments,
                            ScanResult& result);
  void ExtendPlane(MapPlane& mapped, const PlaneSegment& observed_in_map);
  /// Merges into an older plane each of `touched` that grew to overlap a coplanar one (two
  /// pieces of one wall, mapped apart while a gap lay between them): observations and room
  /// members move to the older id; mutex held.
  void MergeDuplicatePlanes(const std::vector<int>& touched);
  void MergePlane(int from, int into);
  static PlaneSegment AsSegment(const MapPlane& plane);
  // Rooms and corridors around a keyframe, and the floor over them; mutex held.
  /// Whether `point` (x, y in M) lies in front of every listed wall (0.3 m margin).
  bool InsideWalls(const std::vector<int>& wall_ids, const Eigen::Vector2d& point) const;
  void UpdateRooms(int keyframe);
  void UpdateFloor();
  double FloorHeight() const;
  /// With more than one level walked: a floor per level (id = level) and the rooms on theirs.
  void SplitFloorsByLevel(SGraph* graph, double ground_floor) const;
  BackendProblem MakeProblem() const;
  /// A doorway's width from the gap in its wall's points around the crossing; 0 if not closed.
  /// Measured on full clouds; once they are thinned, the last width so measured.
  double DoorwayWidthLocked(const Doorway& doorway, const SGraph& graph) const;
  /// Thins the clouds of keyframes that left the optimization's window (BackendConfig).
  void ThinOldCloudsLocked();
  Eigen::Matrix<double, 6, 6> OdometryInformation(const Eigen::Isometry3d& relative) const;

  FrontendConfig frontend_;
  BackendConfig backend_;
  mutable std::mutex mutex_;
  std::mutex optimize_mutex_;  // one optimization at a time

  OdometryBuffer odometry_;  // corrected readings (guard_.correction() applied)
  common::OdometryGuard guard_;
  KeyframeSelector selector_;
  double last_odom_stamp_{-1.0};
  double last_scan_stamp_{-1.0};
  double last_track_check_{-1.0};
  std::uint64_t generation_{0};  // bumped by Reset(): stale optimizations are discarded
  unsigned revision_{0};
  int optimized_keyframes_{0};

  Eigen::Isometry3d map_T_odom_{Eigen::Isometry3d::Identity()};  // map <- corrected odom
  std::vector<Keyframe> keyframes_;
  std::vector<PointList> clouds_;                 // per keyframe, in base_link
  size_t thinned_clouds_{0};                      // the first ones, out of the window: thinned
  mutable std::map<int, double> doorway_widths_;  // by doorway id, measured on full clouds
  std::vector<MapPlane> planes_;
  std::vector<PlaneObservation> observations_;
  std::vector<BackendRoom> rooms_;
  std::vector<std::vector<int>> room_keyframes_;
  BackendFloor floor_;
  LevelTracker levels_;         // the storeys walked (keyframe levels)
  double odometry_scale_{1.0};  // the back end's estimate (BackendProblem::odometry_scale)
};

}  // namespace sgraph
}  // namespace is_graphs
