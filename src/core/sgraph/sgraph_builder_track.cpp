// SGraphBuilder: track loss. While the robot is tracked, the walls it sees are mostly walls
// already mapped (even walking into a new room, those just left stay in view); when nearly all
// are new, the map no longer describes where the robot is (carried elsewhere, an odometry jump)
// and the S-Graph restarts from that scan rather than tie the new walls to the old map.
#include <sstream>

#include "is_graphs/sgraph/sgraph_builder.h"

namespace is_graphs {
namespace sgraph {

bool SGraphBuilder::TrackLost(const ScanResult& result) const {
  return result.num_walls >= frontend_.track_loss_min_walls &&
         result.num_new_walls >= frontend_.track_loss_new_share * result.num_walls;
}

bool SGraphBuilder::TrackCheckDueLocked(double stamp) const {
  return frontend_.detect_track_loss && frontend_.track_check_period > 0.0 &&
         static_cast<int>(keyframes_.size()) >= frontend_.track_loss_min_keyframes &&
         (last_track_check_ < 0.0 || stamp - last_track_check_ >= frontend_.track_check_period);
}

std::vector<MapPlaneView> SGraphBuilder::MapViewsLocked() const {
  std::vector<MapPlaneView> views;
  views.reserve(planes_.size());
  for (const auto& p : planes_) {
    if (p.merged_into >= 0) continue;
    MapPlaneView v;
    v.id = p.plane.id;
    v.plane = p.plane.plane;
    v.covariance = p.plane.covariance;
    v.horizontal = p.horizontal;
    v.start = p.start;
    v.end = p.end;
    v.num_keyframes = p.num_keyframes;
    if (p.last_keyframe >= 0 && !keyframes_.empty())
      v.walked_since = keyframes_.back().path - keyframes_[p.last_keyframe].path;
    views.push_back(v);
  }
  return views;
}

std::vector<PlaneSegment> SGraphBuilder::InMap(const std::vector<PlaneSegment>& segments,
                                               const Eigen::Isometry3d& pose) {
  std::vector<PlaneSegment> out;
  out.reserve(segments.size());
  for (const auto& segment : segments) {
    PlaneSegment in_map = TransformSegment(segment, pose);
    in_map.low = pose.translation().z() + segment.low;  // heights in M (walls are vertical)
    in_map.high = pose.translation().z() + segment.high;
    out.push_back(in_map);
  }
  return out;
}

void SGraphBuilder::CountWallsLocked(const Eigen::Isometry3d& pose,
                                     const std::vector<PlaneSegment>& segments,
                                     ScanResult& result) const {
  const std::vector<Association> associations =
      AssociateScan(InMap(segments, pose), MapViewsLocked(), frontend_);
  for (size_t s = 0; s < segments.size(); ++s) {
    if (segments[s].horizontal) continue;
    ++result.num_walls;
    if (associations[s].index < 0) ++result.num_new_walls;
  }
}

void SGraphBuilder::RestartLocked(double stamp, const Eigen::Isometry3d& odom_pose, PointList cloud,
                                  std::vector<Eigen::Vector3f> slice,
                                  const std::vector<PlaneSegment>& segments, ScanResult& result) {
  std::ostringstream w;
  w << "track lost: " << result.num_new_walls << " of the " << result.num_walls
    << " walls seen match no mapped plane (a kidnapped robot? an odometry jump?): the S-Graph "
       "restarts from this scan";
  ScanResult fresh;
  fresh.preprocess_ms = result.preprocess_ms;
  fresh.extraction_ms = result.extraction_ms;
  fresh.restarted = true;
  fresh.warning = result.warning.empty() ? w.str() : result.warning + "; " + w.str();
  ClearGraphLocked();
  AppendKeyframeLocked(stamp, odom_pose, std::move(cloud), std::move(slice), segments, fresh);
  result = fresh;
}

}  // namespace sgraph
}  // namespace is_graphs
