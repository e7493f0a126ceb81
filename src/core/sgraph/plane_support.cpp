#include "is_graphs/sgraph/plane_support.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace is_graphs {
namespace sgraph {

std::string PlaneSupportClass(const Plane& plane, const Eigen::Isometry3d& bim_T_map,
                              const geometry::TriangleMesh& mesh, double tolerance) {
  const geometry::Plane p = plane.plane.Transformed(bim_T_map);
  const Eigen::Vector3d along_raw = Eigen::Vector3d::UnitZ().cross(p.normal);
  if (along_raw.norm() < 1e-6) return "";
  const Eigen::Vector3d along = along_raw.normalized();
  const double z_offset = bim_T_map.translation().z();
  const Eigen::Vector3d a = bim_T_map * Eigen::Vector3d(plane.start.x(), plane.start.y(), 0.0);
  const Eigen::Vector3d b = bim_T_map * Eigen::Vector3d(plane.end.x(), plane.end.y(), 0.0);
  const double s_lo = std::min(along.dot(a), along.dot(b)) - 0.1;
  const double s_hi = std::max(along.dot(a), along.dot(b)) + 0.1;
  const double z_lo = plane.z_min + z_offset - 0.1, z_hi = plane.z_max + z_offset + 0.1;
  const double min_cos = std::cos(10.0 * M_PI / 180.0);
  std::map<int, double> area;  // object -> area
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Eigen::Vector3i& f = mesh.triangles[t];
    const Eigen::Vector3d& v0 = mesh.vertices[f(0)];
    const Eigen::Vector3d& v1 = mesh.vertices[f(1)];
    const Eigen::Vector3d& v2 = mesh.vertices[f(2)];
    const Eigen::Vector3d cross = (v1 - v0).cross(v2 - v0);
    const double norm = cross.norm();
    if (norm < 1e-9 || std::abs(cross.dot(p.normal)) < min_cos * norm) continue;
    const Eigen::Vector3d c = (v0 + v1 + v2) / 3.0;
    if (std::abs(p.SignedDistance(c)) > tolerance) continue;
    const double s = along.dot(c);
    if (s < s_lo || s > s_hi || c.z() < z_lo || c.z() > z_hi) continue;
    area[mesh.triangle_object[t]] += 0.5 * norm;
  }
  std::map<std::string, double> by_class;
  for (const auto& [object, m2] : area) by_class[mesh.ObjectClass(object)] += m2;
  std::string best;
  double most = 0.0;
  for (const auto& [name, m2] : by_class)
    if (m2 > most) best = name, most = m2;
  return best;
}

}  // namespace sgraph
}  // namespace is_graphs
