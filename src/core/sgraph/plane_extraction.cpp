#include "is_graphs/sgraph/plane_extraction.h"

#include <pcl/ModelCoefficients.h>
#include <pcl/PointIndices.h>
#include <pcl/console/print.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/method_types.h>
#include <pcl/sample_consensus/model_types.h>
#include <pcl/segmentation/sac_segmentation.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "is_graphs/sgraph/floor_check.h"
#include "is_graphs/sgraph/local_surface.h"
#include "is_graphs/sgraph/plane_fit.h"
#include "is_graphs/sgraph/plane_segments.h"

namespace is_graphs {
namespace sgraph {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

/// One constrained RANSAC run over `candidates`; the inliers (indices into the cloud).
std::vector<int> RansacPlane(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& cloud,
                             const std::vector<int>& candidates, int model,
                             const Eigen::Vector3d& axis, const FrontendConfig& config) {
  pcl::SACSegmentation<pcl::PointXYZ> seg;
  seg.setOptimizeCoefficients(false);  // refitted per segment below
  seg.setModelType(model);
  seg.setMethodType(pcl::SAC_RANSAC);
  seg.setDistanceThreshold(config.plane_distance_threshold);
  seg.setMaxIterations(config.ransac_iterations);
  seg.setAxis(axis.cast<float>());
  seg.setEpsAngle(config.plane_max_angle_deg * kDegToRad);
  seg.setInputCloud(cloud);
  pcl::IndicesPtr indices(new pcl::Indices(candidates.begin(), candidates.end()));
  seg.setIndices(indices);
  pcl::PointIndices inliers;
  pcl::ModelCoefficients coefficients;
  // No plane among the candidates is an answer here (empty inliers), not an error, but PCL
  // prints one to stderr for each (on a stair, every scan): its messages are silenced for this
  // call only, unless PCL's verbosity was raised to debug.
  const pcl::console::VERBOSITY_LEVEL verbosity = pcl::console::getVerbosityLevel();
  if (verbosity < pcl::console::L_DEBUG) pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  seg.segment(inliers, coefficients);
  pcl::console::setVerbosityLevel(verbosity);
  return std::vector<int>(inliers.indices.begin(), inliers.indices.end());
}

/// How far above the sensor a wall segment must reach: wall_min_rise, or less where the highest
/// beam cannot see that high at the wall's distance (with a margin for the beam spacing).
double RequiredRise(const geometry::Plane& plane, const Eigen::Vector3d& sensor_origin,
                    const FrontendConfig& config) {
  constexpr double kBeamReachShare = 0.8;
  const double distance = std::abs(plane.SignedDistance(sensor_origin));
  const double reach = distance * std::tan(config.sensor_max_elevation_deg * kDegToRad);
  return std::min(config.wall_min_rise, kBeamReachShare * reach);
}

/// How much of a wall segment's length shows its height: the total width of the columns
/// (kSupportColumn wide, along the wall) whose points rise `min_height` or more. One beam's arc
/// on the ceiling far ahead plus a post beside it spans a wall's extent and height, but shows
/// the height in one column only.
double SupportedLength(const PointList& points, const std::vector<int>& indices,
                       const Eigen::Vector3d& dir, const Eigen::Vector3d& up, double min_height) {
  constexpr double kSupportColumn = 0.25;             // m
  std::map<long, std::pair<double, double>> columns;  // column -> lowest, highest point
  for (int i : indices) {
    const Eigen::Vector3d p = points[i].cast<double>();
    const long column = static_cast<long>(std::floor(dir.dot(p) / kSupportColumn));
    const double h = up.dot(p);
    const auto it = columns.find(column);
    if (it == columns.end()) {
      columns.emplace(column, std::make_pair(h, h));
    } else {
      it->second.first = std::min(it->second.first, h);
      it->second.second = std::max(it->second.second, h);
    }
  }
  double supported = 0.0;
  for (const auto& c : columns)
    if (c.second.second - c.second.first >= min_height) supported += kSupportColumn;
  return supported;
}

/// Refits a segment, orients it to the sensor and fills the extent; false to drop it.
bool MakeSegment(const PointList& points, const std::vector<int>& indices, bool horizontal,
                 const Eigen::Vector3d& up, const Eigen::Vector3d& sensor_origin,
                 const FrontendConfig& config, PlaneSegment& out) {
  const auto fit = FitPlane(points, indices, config.point_sigma, config.max_effective_points,
                            horizontal ? std::nullopt : std::optional<Eigen::Vector3d>(up));
  if (!fit) return false;
  geometry::Plane plane = fit->plane;
  Eigen::Matrix3d information = fit->information;
  Eigen::Matrix4d covariance = fit->covariance;
  if (plane.SignedDistance(sensor_origin) < 0.0) {
    plane = plane.Flipped();
    covariance = CovarianceFromInformation(plane.normal, information);  // same spread
  }
  const double tilt = std::abs(plane.normal.dot(up));
  const double max_angle = config.plane_max_angle_deg * kDegToRad;
  if (horizontal ? tilt < std::cos(max_angle) : tilt > std::sin(max_angle)) return false;
  // Extent: along the wall (horizontal direction in the plane) and along up.
  const Eigen::Vector3d along = horizontal ? Eigen::Vector3d(up.cross(Eigen::Vector3d::UnitX()))
                                           : Eigen::Vector3d(up.cross(plane.normal));
  const Eigen::Vector3d dir = along.normalized();
  double s_min = 1e300, s_max = -1e300, h_min = 1e300, h_max = -1e300;
  for (int i : indices) {
    const Eigen::Vector3d p = points[i].cast<double>();
    const double s = dir.dot(p);
    const double h = up.dot(p);
    s_min = std::min(s_min, s);
    s_max = std::max(s_max, s);
    h_min = std::min(h_min, h);
    h_max = std::max(h_max, h);
  }
  if (!horizontal &&
      (s_max - s_min < config.min_segment_length || h_max - h_min < config.min_segment_height))
    return false;
  if (!horizontal && h_max - up.dot(sensor_origin) < RequiredRise(plane, sensor_origin, config))
    return false;
  if (!horizontal && SupportedLength(points, indices, dir, up, config.min_segment_height) <
                         config.min_segment_support)
    return false;
  const Eigen::Vector3d c = fit->centroid;
  out.plane = plane;
  // The information on the minimal tangent depends on the basis at the normal: recompute for
  // the flipped normal (B changes sign with n, which leaves BᵀHB's blocks unchanged up to sign).
  if (plane.normal.dot(fit->plane.normal) < 0.0) {
    Eigen::Matrix<double, 3, 3> s = Eigen::Matrix3d::Identity();
    const Eigen::Matrix<double, 3, 2> b_old = TangentBasis(fit->plane.normal);
    const Eigen::Matrix<double, 3, 2> b_new = TangentBasis(plane.normal);
    // δn_new = −δn_old, δd_new = −δd_old: tangent coordinates map by Bnewᵀ(−Bold), −1.
    s.topLeftCorner<2, 2>() = -(b_new.transpose() * b_old);
    s(2, 2) = -1.0;
    information = s.transpose().inverse() * information * s.inverse();
    covariance = CovarianceFromInformation(plane.normal, information);
  }
  out.information = information;
  out.covariance = covariance;
  out.horizontal = horizontal;
  out.start = plane.Project(c + (s_min - dir.dot(c)) * dir);
  out.end = plane.Project(c + (s_max - dir.dot(c)) * dir);
  out.low = h_min;
  out.high = h_max;
  out.num_points = static_cast<int>(indices.size());
  return true;
}

}  // namespace

std::vector<PlaneSegment> ExtractPlanes(const PointList& points, const Eigen::Vector3d& up_in,
                                        const Eigen::Vector3d& sensor_origin,
                                        const FrontendConfig& config) {
  std::vector<PlaneSegment> segments;
  if (points.size() < static_cast<size_t>(config.min_plane_points)) return segments;
  const Eigen::Vector3d up = up_in.normalized();
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->resize(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    (*cloud)[i] = pcl::PointXYZ(points[i].x(), points[i].y(), points[i].z());
  std::vector<char> used(points.size(), 0);
  auto remaining = [&](auto keep) {
    std::vector<int> out;
    out.reserve(points.size());
    for (size_t i = 0; i < points.size(); ++i)
      if (!used[i] && keep(i)) out.push_back(static_cast<int>(i));
    return out;
  };

  if (config.extract_floor) {
    // The floor: below the sensor by more than a body height's margin.
    const double sensor_height = up.dot(sensor_origin);
    const auto below =
        remaining([&](size_t i) { return up.dot(points[i].cast<double>()) < sensor_height - 0.3; });
    if (below.size() >= static_cast<size_t>(config.min_plane_points)) {
      const auto inliers = RansacPlane(cloud, below, pcl::SACMODEL_PERPENDICULAR_PLANE, up, config);
      // A band of wall returns is not a floor: it has more wall straight above it.
      if (inliers.size() >= static_cast<size_t>(config.min_plane_points) &&
          FractionCoveredAbove(points, inliers, up, config.voxel_size, 0.5 * config.voxel_size,
                               config.floor_cover_height) <= config.floor_max_covered) {
        for (int i : inliers) used[i] = 1;
        PlaneSegment floor;
        if (MakeSegment(points, inliers, true, up, sensor_origin, config, floor))
          segments.push_back(floor);
      }
    }
  }

  // Inliers that only pass through a wall's distance band (a perpendicular wall at a corner, a
  // door's reveal) would tilt it: they are dropped by the shape of the cloud around them.
  const bool check_surfaces = config.wall_normal_max_angle_deg < 90.0;
  std::optional<LocalSurfaces> surfaces;
  if (check_surfaces) surfaces.emplace(points, config.wall_normal_cell);
  int walls = 0;
  for (int attempt = 0; attempt < 2 * config.max_planes && walls < config.max_planes; ++attempt) {
    const auto candidates = remaining([](size_t) { return true; });
    if (candidates.size() < static_cast<size_t>(config.min_plane_points)) break;
    const auto inliers = RansacPlane(cloud, candidates, pcl::SACMODEL_PARALLEL_PLANE, up, config);
    if (inliers.size() < static_cast<size_t>(config.min_plane_points)) break;
    for (int i : inliers) used[i] = 1;
    // The RANSAC plane's direction, from a quick fit of all inliers, orders the segments.
    const auto whole = FitPlane(points, inliers, config.point_sigma, config.max_effective_points);
    if (!whole) continue;
    const Eigen::Vector3d along = up.cross(whole->plane.normal);
    if (along.norm() < 1e-6) continue;
    for (const auto& part :
         SplitCoplanarSegments(points, inliers, along.normalized(), config.segment_gap)) {
      // Fitted, measured and checked for length on the points on the wall alone: a piece that
      // is mostly corner is no wall (its extent stops short of a corner by up to a cell or two).
      const std::vector<int> on_plane =
          check_surfaces ? surfaces->OnPlane(part, whole->plane.normal,
                                             config.wall_normal_max_angle_deg * kDegToRad)
                         : part;
      if (on_plane.size() < static_cast<size_t>(config.min_plane_points) / 2) continue;
      PlaneSegment segment;
      if (MakeSegment(points, on_plane, false, up, sensor_origin, config, segment)) {
        segments.push_back(segment);
        ++walls;
      }
    }
  }
  return segments;
}

}  // namespace sgraph
}  // namespace is_graphs
