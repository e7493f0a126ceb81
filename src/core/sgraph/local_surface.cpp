#include "is_graphs/sgraph/local_surface.h"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "is_graphs/sgraph/cloud_filter.h"

namespace is_graphs {
namespace sgraph {
namespace {

constexpr int kMinPoints = 5;
// Surroundings whose middle spread is below this share of their largest are a line.
constexpr double kLinearRatio = 0.05;

}  // namespace

LocalSurfaces::LocalSurfaces(const PointList& points, double cell_size)
    : cell_of_point_(points.size(), nullptr) {
  const double inv = 1.0 / cell_size;
  cells_.reserve(points.size() / 4 + 1);
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d p = points[i].cast<double>();
    if (!p.allFinite()) continue;
    const Eigen::Vector3i index((p * inv).array().floor().cast<int>());
    Cell& c = cells_[VoxelKey(index)];
    c.index = index;
    ++c.moments.count;
    c.moments.sum += p;
    c.moments.outer += p * p.transpose();
    cell_of_point_[i] = &c;  // unordered_map nodes are stable
  }
}

const LocalSurfaces::Shape& LocalSurfaces::ShapeOf(Cell& cell) {
  Shape& s = cell.shape;
  if (s.computed) return s;
  s.computed = true;
  Moments m;
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz) {
        const auto it = cells_.find(VoxelKey(cell.index + Eigen::Vector3i(dx, dy, dz)));
        if (it == cells_.end()) continue;
        m.count += it->second.moments.count;
        m.sum += it->second.moments.sum;
        m.outer += it->second.moments.outer;
      }
  if (m.count < kMinPoints) return s;
  const Eigen::Vector3d mean = m.sum / m.count;
  const Eigen::Matrix3d scatter = m.outer - m.count * mean * mean.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  const Eigen::Vector3d l = eig.eigenvalues();  // ascending
  if (!(l(2) > 0.0)) return s;
  s.known = true;
  s.linear = l(1) < kLinearRatio * l(2);
  s.axis = s.linear ? eig.eigenvectors().col(2) : eig.eigenvectors().col(0);
  return s;
}

std::vector<int> LocalSurfaces::OnPlane(const std::vector<int>& indices,
                                        const Eigen::Vector3d& normal, double max_angle_rad) {
  const double cos_max = std::cos(max_angle_rad), sin_max = std::sin(max_angle_rad);
  std::vector<int> kept;
  kept.reserve(indices.size());
  for (int i : indices) {
    Cell* cell = cell_of_point_[i];
    if (cell == nullptr) continue;
    const Shape& s = ShapeOf(*cell);
    const double c = std::abs(s.axis.dot(normal));
    if (!s.known || (s.linear ? c <= sin_max : c >= cos_max)) kept.push_back(i);
  }
  return kept;
}

}  // namespace sgraph
}  // namespace is_graphs
