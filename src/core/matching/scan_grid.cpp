#include "is_graphs/matching/scan_grid.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace is_graphs {
namespace matching {

ScanGrid::ScanGrid(const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& segments,
                   double resolution, double sigma, int levels)
    : resolution_(resolution) {
  if (segments.empty()) return;
  Eigen::AlignedBox2d box;
  for (const auto& [a, b] : segments) box.extend(a), box.extend(b);
  const double reach = 4.0 * sigma + resolution;
  origin_ = box.min() - Eigen::Vector2d::Constant(reach);
  width_ = static_cast<int>(std::ceil((box.sizes().x() + 2.0 * reach) / resolution)) + 1;
  height_ = static_cast<int>(std::ceil((box.sizes().y() + 2.0 * reach) / resolution)) + 1;
  walls_ = Eigen::AlignedBox2i(Cell(box.min()), Cell(box.max()));
  // Level 0: each segment raised into the cells within `reach` of it.
  Level base;
  base.width = width_, base.height = height_;
  base.cells.assign(static_cast<size_t>(width_) * height_, 0);
  const int r = static_cast<int>(std::ceil(reach / resolution));
  for (const auto& [a, b] : segments) {
    const Eigen::Vector2d ab = b - a;
    const double len2 = std::max(ab.squaredNorm(), 1e-12);
    const Eigen::Vector2i lo = Cell(a.cwiseMin(b)) - Eigen::Vector2i::Constant(r);
    const Eigen::Vector2i hi = Cell(a.cwiseMax(b)) + Eigen::Vector2i::Constant(r);
    for (int v = std::max(lo.y(), 0); v <= std::min(hi.y(), height_ - 1); ++v)
      for (int u = std::max(lo.x(), 0); u <= std::min(hi.x(), width_ - 1); ++u) {
        const Eigen::Vector2d p = Centre({u, v});
        const double t = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
        const double d2 = (a + t * ab - p).squaredNorm();
        if (d2 > reach * reach) continue;
        const double value = std::exp(-d2 / (2.0 * sigma * sigma));
        const auto q = static_cast<std::uint8_t>(std::min(255.0, std::ceil(255.0 * value)));
        std::uint8_t& cell = base.cells[static_cast<size_t>(v) * width_ + u];
        cell = std::max(cell, q);
      }
  }
  pyramid_.push_back(std::move(base));
  // Level h from level h-1: the max of four windows of half the size.
  for (int h = 1; h < levels; ++h) {
    const Level& below = pyramid_.back();
    const int half = 1 << (h - 1);
    Level l;
    l.pad = (1 << h) - 1;
    l.width = width_ + l.pad, l.height = height_ + l.pad;
    l.cells.assign(static_cast<size_t>(l.width) * l.height, 0);
    auto at = [&](int u, int v) {
      const int x = u + below.pad, y = v + below.pad;
      if (x < 0 || y < 0 || x >= below.width || y >= below.height) return 0;
      return static_cast<int>(below.cells[static_cast<size_t>(y) * below.width + x]);
    };
    for (int y = 0; y < l.height; ++y)
      for (int x = 0; x < l.width; ++x) {
        const int u = x - l.pad, v = y - l.pad;
        const int m = std::max(std::max(at(u, v), at(u + half, v)),
                               std::max(at(u, v + half), at(u + half, v + half)));
        l.cells[static_cast<size_t>(y) * l.width + x] = static_cast<std::uint8_t>(m);
      }
    pyramid_.push_back(std::move(l));
  }
}

Eigen::Vector2i ScanGrid::Cell(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d c = (p - origin_) / resolution_;
  return {static_cast<int>(std::floor(c.x())), static_cast<int>(std::floor(c.y()))};
}

Eigen::Vector2d ScanGrid::Centre(const Eigen::Vector2i& c) const {
  return origin_ + resolution_ * (c.cast<double>() + Eigen::Vector2d::Constant(0.5));
}

}  // namespace matching
}  // namespace is_graphs
