#pragma once

#include <Eigen/Geometry>
#include <limits>
#include <vector>

#include "is_graphs/geometry/plane.h"
#include "is_graphs/sgraph/frontend_config.h"
#include "is_graphs/sgraph/plane_extraction.h"

namespace is_graphs {
namespace sgraph {

/// What association needs of a mapped plane (in M, z up).
struct MapPlaneView {
  int id{0};
  geometry::Plane plane;
  Eigen::Matrix4d covariance{Eigen::Matrix4d::Identity()};
  bool horizontal{false};
  Eigen::Vector3d start{Eigen::Vector3d::Zero()};  // extent along the wall
  Eigen::Vector3d end{Eigen::Vector3d::Zero()};
  double walked_since{0.0};  // m of odometry path since a keyframe last observed it
  int num_keyframes{0};      // keyframes that observed it
};

struct Association {
  int index{-1};  // into the mapped list; -1: a new plane
  double distance2{std::numeric_limits<double>::infinity()};  // squared Mahalanobis
};

/// The segment (in frame A) expressed in frame B: plane, covariance, extent points.
PlaneSegment TransformSegment(const PlaneSegment& segment, const Eigen::Isometry3d& b_T_a);

/// Squared Mahalanobis distance between an observed plane and a mapped one, on the minimal
/// tangent at the mapped normal: e = (Bᵀ(n_o − n_m), d_o − d_m), Σ = Σ_m + Σ_o + floors.
/// Infinite when the normals are more than 30° apart (opposite faces never match).
double PlaneMahalanobis2(const PlaneSegment& observed, const MapPlaneView& mapped,
                         const FrontendConfig& config);

/// The gap (m) between the observed segment and the mapped extent along the mapped wall;
/// ≤ 0 when they overlap. Zero for horizontal planes.
double SegmentGap(const PlaneSegment& observed, const MapPlaneView& mapped);

/// The mapped plane of least Mahalanobis distance within the chi-square gate whose extent the
/// segment overlaps or nearly touches (SegmentGap ≤ association_max_gap); index −1 if none.
/// Mapped planes listed in `excluded` (indices) are not considered.
Association AssociatePlane(const PlaneSegment& observed_in_map,
                           const std::vector<MapPlaneView>& mapped, const FrontendConfig& config,
                           const std::vector<int>& excluded = {});

/// Whether two segments of one scan can lie on one plane: each one's middle within
/// `tolerance` of the other's plane. Within a scan the pose error is common to both, so the
/// offset between them is measured as precisely as the points (a wall and a window set back
/// 12 cm in it are two planes even where the map's gate, widened for drift, admits both).
bool CoplanarInScan(const PlaneSegment& a, const PlaneSegment& b, double tolerance);

/// Associates all segments of one scan (in M): each as AssociatePlane, but two segments that
/// are not coplanar (CoplanarInScan with association_coplanar_tolerance) never take one mapped
/// plane; the one further in Mahalanobis distance tries the next plane or becomes a new one.
std::vector<Association> AssociateScan(const std::vector<PlaneSegment>& observed_in_map,
                                       const std::vector<MapPlaneView>& mapped,
                                       const FrontendConfig& config);

}  // namespace sgraph
}  // namespace is_graphs
