#pragma once

#include <Eigen/Core>
#include <vector>

#include "is_graphs/geometry/plane.h"
#include "is_graphs/sgraph/frontend_config.h"
#include "is_graphs/sgraph/point_types.h"

namespace is_graphs {
namespace sgraph {

/// One plane segment seen in a scan, in the frame of the scan's points (base_link).
struct PlaneSegment {
  geometry::Plane plane;                                     // normal towards the sensor
  Eigen::Matrix3d information{Eigen::Matrix3d::Identity()};  // minimal tangent (plane_fit.h)
  Eigen::Matrix4d covariance{Eigen::Matrix4d::Identity()};   // of (n, d)
  bool horizontal{false};                                    // the floor
  Eigen::Vector3d start{Eigen::Vector3d::Zero()};  // extreme points along the wall direction
  Eigen::Vector3d end{Eigen::Vector3d::Zero()};    // (on the plane, at the points' mean height)
  double low{0.0};                                 // extent along `up`
  double high{0.0};
  int num_points{0};
};

/// Extracts the vertical wall planes (any azimuth) and the floor from a filtered cloud.
///
/// Method: sequential RANSAC (PCL SACSegmentation) with constrained models: the floor first,
/// a plane perpendicular to `up` among points below the sensor; then walls, planes parallel to
/// `up` (SACMODEL_PARALLEL_PLANE), each found plane's inliers removed before the next. A
/// wall's inliers whose surroundings face another way (a perpendicular wall's points at a
/// corner, a door's reveal, inside the RANSAC band) are dropped (local_surface.h): they tilt a
/// short piece by degrees. The rest are split into coplanar but disjoint segments
/// (plane_segments.h), and each segment is refitted by total least squares with its covariance
/// (plane_fit.h). Segments shorter or lower than configured are dropped. Normals point to the
/// sensor's side.
///
/// `up` is the gravity direction in the points' frame, `sensor_origin` the sensor's position.
std::vector<PlaneSegment> ExtractPlanes(const PointList& points, const Eigen::Vector3d& up,
                                        const Eigen::Vector3d& sensor_origin,
                                        const FrontendConfig& config);

}  // namespace sgraph
}  // namespace is_graphs
