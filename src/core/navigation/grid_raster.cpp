#include "grid_raster.h"

#include <algorithm>
#include <cmath>

namespace is_graphs {
namespace navigation {
namespace {

/// Sutherland-Hodgman against one horizontal plane: keeps z >= z0 (above) or z <= z0.
std::vector<Eigen::Vector3d> ClipZ(const std::vector<Eigen::Vector3d>& in, double z0,
                                   bool keep_above) {
  std::vector<Eigen::Vector3d> out;
  const auto inside = [&](const Eigen::Vector3d& p) {
    return keep_above ? p.z() >= z0 : p.z() <= z0;
  };
  for (size_t i = 0; i < in.size(); ++i) {
    const Eigen::Vector3d& a = in[i];
    const Eigen::Vector3d& b = in[(i + 1) % in.size()];
    if (inside(a)) out.push_back(a);
    if (inside(a) != inside(b)) out.push_back(a + (b - a) * ((z0 - a.z()) / (b.z() - a.z())));
  }
  return out;
}

}  // namespace

void GridRaster::FillPolygon(const std::vector<Eigen::Vector2d>& polygon, std::int8_t value) {
  if (polygon.size() < 3) return;
  double y_min = polygon[0].y(), y_max = y_min;
  for (const auto& p : polygon) y_min = std::min(y_min, p.y()), y_max = std::max(y_max, p.y());
  const double res = grid_.resolution;
  const int row0 = std::max(0, static_cast<int>(std::floor((y_min - grid_.origin.y()) / res)));
  const int row1 =
      std::min(grid_.height - 1, static_cast<int>(std::floor((y_max - grid_.origin.y()) / res)));
  std::vector<double> xs;
  for (int iy = row0; iy <= row1; ++iy) {
    const double y = grid_.origin.y() + (iy + 0.5) * res;
    xs.clear();
    for (size_t i = 0; i < polygon.size(); ++i) {
      const Eigen::Vector2d& a = polygon[i];
      const Eigen::Vector2d& b = polygon[(i + 1) % polygon.size()];
      if ((a.y() <= y) != (b.y() <= y))
        xs.push_back(a.x() + (y - a.y()) / (b.y() - a.y()) * (b.x() - a.x()));
    }
    std::sort(xs.begin(), xs.end());
    for (size_t k = 0; k + 1 < xs.size(); k += 2) {
      const int c0 =
          std::max(0, static_cast<int>(std::ceil((xs[k] - grid_.origin.x()) / res - 0.5)));
      const int c1 =
          std::min(grid_.width - 1,
                   static_cast<int>(std::floor((xs[k + 1] - grid_.origin.x()) / res - 0.5)));
      for (int ix = c0; ix <= c1; ++ix) grid_.At(ix, iy) = value;
    }
  }
}

void GridRaster::MarkSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                             std::int8_t value) {
  const int steps = 1 + static_cast<int>(std::ceil((b - a).norm() / (0.25 * grid_.resolution)));
  for (int i = 0; i <= steps; ++i) Set(grid_.CellOf(a + (b - a) * (double(i) / steps)), value);
}

void GridRaster::FillSection(const std::array<Eigen::Vector3d, 3>& triangle, double z0, double z1,
                             std::int8_t value) {
  const double lo = std::min({triangle[0].z(), triangle[1].z(), triangle[2].z()});
  const double hi = std::max({triangle[0].z(), triangle[1].z(), triangle[2].z()});
  if (hi < z0 || lo > z1) return;
  std::vector<Eigen::Vector3d> section(triangle.begin(), triangle.end());
  if (lo < z0) section = ClipZ(section, z0, true);
  if (hi > z1) section = ClipZ(section, z1, false);
  if (section.empty()) return;
  std::vector<Eigen::Vector2d> outline;
  for (const auto& p : section) outline.push_back(p.head<2>());
  for (size_t i = 0; i < outline.size(); ++i)
    MarkSegment(outline[i], outline[(i + 1) % outline.size()], value);
  FillPolygon(outline, value);
}

}  // namespace navigation
}  // namespace is_graphs
