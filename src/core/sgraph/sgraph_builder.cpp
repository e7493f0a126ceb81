#include "is_graphs/sgraph/sgraph_builder.h"
#include "is_graphs/sgraph/scan_slice.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "is_graphs/sgraph/cloud_filter.h"
#include "is_graphs/sgraph/deskew.h"
#include "is_graphs/sgraph/plane_association.h"
#include "is_graphs/sgraph/plane_fit.h"
#include "is_graphs/sgraph/scan_consistency.h"

namespace is_graphs {
namespace sgraph {

SGraphBuilder::SGraphBuilder(const FrontendConfig& frontend, const BackendConfig& backend)
    : frontend_(frontend),
      backend_(backend),
      guard_(frontend.odometry_guard),
      selector_(frontend.keyframe_distance, frontend.keyframe_angle_deg * M_PI / 180.0),
      levels_(frontend.levels) {}

void SGraphBuilder::Reset() {
  std::lock_guard<std::mutex> lock(mutex_);
  ResetLocked();
}

void SGraphBuilder::ResetLocked() {
  last_track_check_ = -1.0;
  odometry_.Clear();
  if (guard_.last_stamp() >= 0.0 && last_odom_stamp_ >= 0.0 &&
      guard_.last_stamp() <= last_odom_stamp_)
    guard_.Reset();  // not when time went back: the guard started over on that message itself
  selector_.Reset();
  last_odom_stamp_ = -1.0;
  last_scan_stamp_ = -1.0;
  ClearGraphLocked();
}

void SGraphBuilder::ClearGraphLocked() {
  ++generation_;
  optimized_keyframes_ = 0;
  map_T_odom_ = Eigen::Isometry3d::Identity();
  keyframes_.clear();
  clouds_.clear();
  thinned_clouds_ = 0;
  doorway_widths_.clear();
  planes_.clear();
  observations_.clear();
  rooms_.clear();
  room_keyframes_.clear();
  floor_ = BackendFloor();
  levels_.Reset();
}

SGraphBuilder::OdometryResult SGraphBuilder::AddOdometry(double stamp,
                                                         const Eigen::Isometry3d& odom_T_base) {
  std::lock_guard<std::mutex> lock(mutex_);
  OdometryResult result;
  std::ostringstream warning;
  const common::OdometryGuard::Result checked = guard_.Check(stamp, odom_T_base);
  result.verdict = checked.verdict;
  if (!checked.usable()) {
    result.accepted = false;
    result.warning = "odometry " + std::string(common::ToString(checked.verdict)) + " (" +
                     checked.message + "): skipped";
    return result;
  }
  if (checked.verdict == common::OdometryGuard::Verdict::kBridged)
    warning << checked.message << "; ";
  if (last_odom_stamp_ >= 0.0 && stamp < last_odom_stamp_ - frontend_.time_reset_threshold) {
    warning << "odometry time went backwards by " << last_odom_stamp_ - stamp
            << " s (a restarted bag?): the S-Graph is reset";
    ResetLocked();
    result.reset = true;
  } else if (last_odom_stamp_ >= 0.0 && stamp <= last_odom_stamp_) {
    result.accepted = false;
    result.warning = "odometry out of order (stamp not after the last one): skipped";
    return result;
  } else if (last_odom_stamp_ >= 0.0 && stamp - last_odom_stamp_ > frontend_.max_odom_gap) {
    warning << "gap of " << stamp - last_odom_stamp_
            << " s in odometry: scans inside it are skipped";
  }
  result.odom_T_base = checked.odom_T_base;
  odometry_.Add(stamp, checked.odom_T_base);
  last_odom_stamp_ = stamp;
  result.warning = warning.str();
  return result;
}

Eigen::Matrix<double, 6, 6> SGraphBuilder::OdometryInformation(
    const Eigen::Isometry3d& relative) const {
  const double distance = relative.translation().norm();
  const double angle = Eigen::AngleAxisd(relative.linear()).angle();
  const double st = backend_.odom_sigma_translation * std::max(distance, 0.2) + 0.002;
  const double syaw = backend_.odom_sigma_rotation * std::max(distance, 0.2) + 0.02 * angle + 0.001;
  Eigen::Matrix<double, 6, 1> sigma;
  sigma << st, st, backend_.odom_sigma_z, backend_.odom_sigma_roll_pitch,
      backend_.odom_sigma_roll_pitch, syaw;
  return sigma.cwiseInverse().cwiseAbs2().asDiagonal();
}

SGraphBuilder::ScanResult SGraphBuilder::AddScan(const Scan& scan,
                                                 const Eigen::Isometry3d& base_T_sensor) {
  ScanResult result;
  if (scan.points.empty()) {
    result.warning = "empty cloud: skipped";
    return result;
  }
  if (!std::isfinite(scan.stamp)) {
    result.warning = "cloud with a non-finite stamp: skipped";
    return result;
  }
  // Odometry and time checks under the lock; the heavy work on a copy of the poses without it.
  OdometryBuffer odometry(0.0);
  Eigen::Isometry3d odom_pose;
  bool keyframe = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (last_scan_stamp_ >= 0.0 && scan.stamp < last_scan_stamp_ - frontend_.time_reset_threshold) {
      ResetLocked();
      result.warning = "cloud time went backwards (a restarted bag?): the S-Graph is reset";
      return result;
    }
    if (last_scan_stamp_ >= 0.0 && scan.stamp <= last_scan_stamp_) {
      result.warning = "cloud out of order (stamp not after the last one): skipped";
      return result;
    }
    const auto pose =
        odometry_.At(scan.stamp, frontend_.max_odom_gap, frontend_.max_odom_extrapolation);
    if (!pose) {
      std::ostringstream s;
      s << "no odometry at the cloud's time " << std::fixed << scan.stamp
        << " (gap, or odometry not started): skipped";
      result.warning = s.str();
      return result;
    }
    last_scan_stamp_ = scan.stamp;
    odom_pose = *pose;
    keyframe = selector_.IsKeyframe(odom_pose);
    // Between keyframes (a robot standing still, or carried) the track is checked this often.
    if (!keyframe && !TrackCheckDueLocked(scan.stamp)) {
      result.status = ScanStatus::kNotKeyframe;
      return result;
    }
    last_track_check_ = scan.stamp;
    odometry = odometry_;
  }

  using Clock = std::chrono::steady_clock;
  const auto ms_since = [](Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  };
  auto t0 = Clock::now();
  const auto deskewed = DeskewToBase(scan, base_T_sensor, [&](double t) {
    return odometry.At(t, frontend_.max_odom_gap, frontend_.max_odom_extrapolation);
  });
  if (!deskewed) {
    result.warning = "odometry does not cover the cloud's time span: skipped";
    return result;
  }
  const size_t dropped = scan.points.size() - deskewed->size();
  const Eigen::Vector3f origin = base_T_sensor.translation().cast<float>();
  const PointList ranged = RangeFilter(*deskewed, origin, frontend_.min_range, frontend_.max_range);
  if (ranged.size() < static_cast<size_t>(frontend_.min_plane_points)) {
    result.warning = "cloud has too few valid points in range: skipped";
    return result;
  }
  if (dropped > 0) result.warning = std::to_string(dropped) + " non-finite points dropped";
  const PointList filtered = VoxelFilter(ranged, frontend_.voxel_size);
  result.preprocess_ms = ms_since(t0);
  t0 = Clock::now();
  const Eigen::Vector3d up = odom_pose.linear().transpose() * Eigen::Vector3d::UnitZ();
  const std::vector<PlaneSegment> segments =
      ExtractPlanes(filtered, up, base_T_sensor.translation(), frontend_);
  result.extraction_ms = ms_since(t0);
  PointList map_points = VoxelFilter(filtered, frontend_.map_voxel_size);
  std::vector<Eigen::Vector3f> slice = ScanSlice(ranged, up, frontend_);

  std::lock_guard<std::mutex> lock(mutex_);
  if (last_scan_stamp_ != scan.stamp) {  // reset meanwhile
    result.warning = "the S-Graph was reset while the cloud was processed: skipped";
    return result;
  }
  if (!keyframe) {  // a track check only: nothing is added unless the track is lost
    CountWallsLocked(map_T_odom_ * odom_pose, segments, result);
    if (!TrackLost(result)) {
      result.status = ScanStatus::kNotKeyframe;  // with the walls counted
      return result;
    }
    selector_.Accept(odom_pose);
    RestartLocked(scan.stamp, odom_pose, std::move(map_points), std::move(slice), segments,
                  result);
    return result;
  }
  selector_.Accept(odom_pose);
  const bool can_lose_track = frontend_.detect_track_loss && static_cast<int>(keyframes_.size()) >=
                                                                 frontend_.track_loss_min_keyframes;
  PointList cloud_copy;
  if (can_lose_track) cloud_copy = map_points;
  std::vector<Eigen::Vector3f> slice_copy;
  if (can_lose_track) slice_copy = slice;
  AppendKeyframeLocked(scan.stamp, odom_pose, std::move(map_points), std::move(slice), segments,
                       result);
  if (can_lose_track && TrackLost(result))
    RestartLocked(scan.stamp, odom_pose, std::move(cloud_copy), std::move(slice_copy), segments,
                  result);
  return result;
}

void SGraphBuilder::AppendKeyframeLocked(double stamp, const Eigen::Isometry3d& odom_pose,
                                         PointList cloud, std::vector<Eigen::Vector3f> slice,
                                         const std::vector<PlaneSegment>& segments,
                                         ScanResult& result) {
  using Clock = std::chrono::steady_clock;
  const auto ms_since = [](Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  };
  Keyframe kf;
  kf.id = static_cast<int>(keyframes_.size());
  kf.stamp = stamp;
  kf.odom_pose = odom_pose;
  kf.pose = map_T_odom_ * odom_pose;
  if (!keyframes_.empty()) {
    const Keyframe& prev = keyframes_.back();
    kf.previous = prev.id;
    kf.relative_odom = prev.odom_pose.inverse() * odom_pose;
    kf.odom_information = OdometryInformation(kf.relative_odom);
    // Predicted from the previous keyframe with the odometry's estimated distance scale.
    Eigen::Isometry3d step = kf.relative_odom;
    step.translation() *= odometry_scale_;
    kf.pose = prev.pose * step;
    kf.path = prev.path + kf.relative_odom.translation().norm();
  }
  kf.level = levels_.Add(Eigen::Vector3d(kf.pose.translation()));
  // Only the newest slice_keyframes keep their slice (bounded memory and message size).
  if (frontend_.slice_keyframes > 0) kf.slice = std::move(slice);
  const size_t older = static_cast<size_t>(std::max(0, frontend_.slice_keyframes - 1));
  for (size_t i = 0; i + older < keyframes_.size(); ++i) keyframes_[i].slice.clear();
  const int id = kf.id;
  keyframes_.push_back(std::move(kf));
  clouds_.push_back(std::move(cloud));
  ThinOldCloudsLocked();
  result.status = ScanStatus::kKeyframe;
  result.keyframe = id;
  auto t0 = Clock::now();
  AddPlaneObservations(id, segments, result);
  result.association_ms = ms_since(t0);
  t0 = Clock::now();
  if (frontend_.detect_rooms) UpdateRooms(id);
  result.rooms_ms = ms_since(t0);
}

void SGraphBuilder::AddPlaneObservations(int keyframe, const std::vector<PlaneSegment>& segments,
                                         ScanResult& result) {
  const std::vector<MapPlaneView> views = MapViewsLocked();
  const std::vector<PlaneSegment> in_map_segments = InMap(segments, keyframes_[keyframe].pose);
  // Two coplanar segments of one scan may land on one mapped plane (a wall behind an
  // obstacle), two parallel ones apart may not.
  const std::vector<Association> associations = AssociateScan(in_map_segments, views, frontend_);
  const std::vector<int> contradicted =
      ContradictedWalls(in_map_segments, views, associations, frontend_).contradicted;
  std::vector<int> touched;  // planes observed now: they may have grown into a duplicate
  for (size_t s = 0; s < segments.size(); ++s) {
    if (std::binary_search(contradicted.begin(), contradicted.end(), static_cast<int>(s))) {
      ++result.num_contradicted;  // turned since it was mapped (a door leaf): not used
      continue;
    }
    const PlaneSegment& segment = segments[s];
    const PlaneSegment& in_map = in_map_segments[s];
    ++result.num_segments;
    const Association& a = associations[s];
    int plane_id;
    if (a.index >= 0) {
      plane_id = views[a.index].id;
      ExtendPlane(planes_[plane_id], in_map);
    } else {
      MapPlane mp;
      mp.plane.id = static_cast<int>(planes_.size());
      mp.plane.plane = in_map.plane;
      mp.plane.covariance = in_map.covariance;
      mp.plane.orientation = geometry::ClassifyOrientation(in_map.plane.normal);
      mp.horizontal = in_map.horizontal;
      mp.start = in_map.start;
      mp.end = in_map.end;
      mp.plane.z_min = in_map.horizontal ? in_map.plane.d : in_map.low;
      mp.plane.z_max = in_map.horizontal ? in_map.plane.d : in_map.high;
      mp.plane.num_points = in_map.num_points;
      mp.information = in_map.information;
      mp.plane.start = mp.start.head<2>();
      mp.plane.end = mp.end.head<2>();
      plane_id = mp.plane.id;
      planes_.push_back(mp);
      ++result.num_new_planes;
      if (!segment.horizontal) ++result.num_new_walls;
    }
    if (!segment.horizontal) ++result.num_walls;
    if (planes_[plane_id].last_keyframe != keyframe) ++planes_[plane_id].num_keyframes;
    planes_[plane_id].last_keyframe = keyframe;
    PlaneObservation o;
    o.keyframe = keyframe;
    o.plane = plane_id;
    o.local = segment.plane;
    o.information = segment.information;
    observations_.push_back(o);
    touched.push_back(plane_id);
  }
  MergeDuplicatePlanes(touched);
}

void SGraphBuilder::ExtendPlane(MapPlane& mapped, const PlaneSegment& in_map) {
  mapped.plane.num_points += in_map.num_points;
  // Fuse the information (both on the tangent at the mapped normal, to first order).
  const Eigen::Matrix3d cov = TangentCovariance(mapped.plane.plane.normal, in_map.covariance);
  mapped.information += (cov + 1e-12 * Eigen::Matrix3d::Identity()).inverse();
  mapped.plane.covariance =
      CovarianceFromInformation(mapped.plane.plane.normal, mapped.information);
  if (mapped.horizontal) return;
  mapped.plane.z_min = std::min(mapped.plane.z_min, in_map.low);
  mapped.plane.z_max = std::max(mapped.plane.z_max, in_map.high);
  const Eigen::Vector3d along = Eigen::Vector3d::UnitZ().cross(mapped.plane.plane.normal);
  if (along.norm() < 1e-6) return;
  const Eigen::Vector3d dir = along.normalized();
  double lo = dir.dot(mapped.start), hi = dir.dot(mapped.end);
  Eigen::Vector3d lo_p = mapped.start, hi_p = mapped.end;
  if (lo > hi) {
    std::swap(lo, hi);
    std::swap(lo_p, hi_p);
  }
  for (const Eigen::Vector3d& p : {in_map.start, in_map.end}) {
    const double s = dir.dot(p);
    if (s < lo) lo = s, lo_p = p;
    if (s > hi) hi = s, hi_p = p;
  }
  mapped.start = mapped.plane.plane.Project(lo_p);
  mapped.end = mapped.plane.plane.Project(hi_p);
  mapped.plane.start = mapped.start.head<2>();
  mapped.plane.end = mapped.end.head<2>();
}

}  // namespace sgraph
}  // namespace is_graphs
