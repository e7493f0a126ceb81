#include "is_graphs/sgraph/plane_association.h"

#include <algorithm>
#include <cmath>

#include "is_graphs/sgraph/plane_fit.h"

namespace is_graphs {
namespace sgraph {

PlaneSegment TransformSegment(const PlaneSegment& segment, const Eigen::Isometry3d& b_T_a) {
  PlaneSegment out = segment;
  out.plane = segment.plane.Transformed(b_T_a);
  out.covariance = TransformPlaneCovariance(segment.plane, segment.covariance, b_T_a);
  out.start = b_T_a * segment.start;
  out.end = b_T_a * segment.end;
  // The information lives on the tangent at the normal: recompute it from the covariance.
  const Eigen::Matrix3d cov = TangentCovariance(out.plane.normal, out.covariance);
  out.information = (cov + 1e-12 * Eigen::Matrix3d::Identity()).inverse();
  return out;
}

double PlaneMahalanobis2(const PlaneSegment& observed, const MapPlaneView& mapped,
                         const FrontendConfig& config) {
  const Eigen::Vector3d& nm = mapped.plane.normal;
  if (observed.plane.normal.dot(nm) < std::cos(30.0 * M_PI / 180.0))
    return std::numeric_limits<double>::infinity();
  const Eigen::Matrix<double, 3, 2> basis = TangentBasis(nm);
  Eigen::Vector3d e;
  e.head<2>() = basis.transpose() * (observed.plane.normal - nm);
  e(2) = observed.plane.d - mapped.plane.d;
  const double sa = config.association_min_sigma_angle_deg * M_PI / 180.0;
  const double sd = config.association_min_sigma_d;
  Eigen::Matrix3d cov = TangentCovariance(nm, mapped.covariance + observed.covariance);
  cov += Eigen::Vector3d(sa * sa, sa * sa, sd * sd).asDiagonal();
  return e.dot(cov.ldlt().solve(e));
}

double SegmentGap(const PlaneSegment& observed, const MapPlaneView& mapped) {
  if (mapped.horizontal || observed.horizontal) return 0.0;
  const Eigen::Vector3d along = Eigen::Vector3d::UnitZ().cross(mapped.plane.normal);
  if (along.norm() < 1e-6) return 0.0;
  const Eigen::Vector3d dir = along.normalized();
  const double m0 = dir.dot(mapped.start), m1 = dir.dot(mapped.end);
  const double o0 = dir.dot(observed.start), o1 = dir.dot(observed.end);
  const double m_lo = std::min(m0, m1), m_hi = std::max(m0, m1);
  const double o_lo = std::min(o0, o1), o_hi = std::max(o0, o1);
  return std::max(o_lo - m_hi, m_lo - o_hi);
}

Association AssociatePlane(const PlaneSegment& observed_in_map,
                           const std::vector<MapPlaneView>& mapped, const FrontendConfig& config,
                           const std::vector<int>& excluded) {
  Association best;
  for (size_t i = 0; i < mapped.size(); ++i) {
    if (mapped[i].horizontal != observed_in_map.horizontal) continue;
    if (std::find(excluded.begin(), excluded.end(), static_cast<int>(i)) != excluded.end())
      continue;
    const double m2 = PlaneMahalanobis2(observed_in_map, mapped[i], config);
    if (!(m2 <= config.association_chi2) || m2 >= best.distance2) continue;
    if (SegmentGap(observed_in_map, mapped[i]) > config.association_max_gap) continue;
    best.index = static_cast<int>(i);
    best.distance2 = m2;
  }
  return best;
}

bool CoplanarInScan(const PlaneSegment& a, const PlaneSegment& b, double tolerance) {
  const Eigen::Vector3d mid_a = 0.5 * (a.start + a.end), mid_b = 0.5 * (b.start + b.end);
  return std::abs(a.plane.SignedDistance(mid_b)) <= tolerance &&
         std::abs(b.plane.SignedDistance(mid_a)) <= tolerance;
}

std::vector<Association> AssociateScan(const std::vector<PlaneSegment>& observed_in_map,
                                       const std::vector<MapPlaneView>& mapped,
                                       const FrontendConfig& config) {
  const size_t n = observed_in_map.size();
  std::vector<Association> result(n);
  std::vector<std::vector<int>> excluded(n);
  for (size_t i = 0; i < n; ++i) result[i] = AssociatePlane(observed_in_map[i], mapped, config);
  // Each round moves one segment off a plane it shares with a non-coplanar one; a segment is
  // excluded from at most every mapped plane, so this ends.
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t i = 0; i < n && !changed; ++i) {
      for (size_t j = i + 1; j < n && !changed; ++j) {
        if (result[i].index < 0 || result[i].index != result[j].index) continue;
        if (observed_in_map[i].horizontal || CoplanarInScan(observed_in_map[i], observed_in_map[j],
                                                            config.association_coplanar_tolerance))
          continue;
        const size_t loser = result[i].distance2 <= result[j].distance2 ? j : i;
        excluded[loser].push_back(result[loser].index);
        result[loser] = AssociatePlane(observed_in_map[loser], mapped, config, excluded[loser]);
        changed = true;
      }
    }
  }
  return result;
}

}  // namespace sgraph
}  // namespace is_graphs
