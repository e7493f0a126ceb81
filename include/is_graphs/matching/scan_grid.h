#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace is_graphs {
namespace matching {

/// A storey's wall-surfaces as a score grid: each cell holds exp(-d² / 2σ²) for d the distance
/// from its centre to the nearest segment, quantized upwards to 1/255; and its max-pooled
/// pyramid (Cartographer's precomputation grids): level h holds at every cell (u, v) the max of
/// the cells [u, u + 2^h) x [v, v + 2^h), so the mean of level h over a scan's cells bounds the
/// scan's score at every translation of that square. Cells beyond the grid (more than 4σ from
/// every wall) count 0 (their true value is below e^-8).
class ScanGrid {
 public:
  ScanGrid() = default;
  /// `segments`: pairs of 2-D end points; `levels` pyramid levels (1: the grid alone).
  ScanGrid(const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& segments,
           double resolution, double sigma, int levels);

  bool empty() const { return width_ == 0; }
  int levels() const { return static_cast<int>(pyramid_.size()); }
  double resolution() const { return resolution_; }
  /// The cell holding `p` (may lie outside the grid).
  Eigen::Vector2i Cell(const Eigen::Vector2d& p) const;
  /// The centre of cell `c`.
  Eigen::Vector2d Centre(const Eigen::Vector2i& c) const;
  /// The walls' extent in cells (first and last cell holding a wall's point).
  const Eigen::AlignedBox2i& walls() const { return walls_; }
  /// Level h's value at (u, v), 0..255 (0 beyond the grid).
  int At(int level, int u, int v) const {
    const Level& l = pyramid_[level];
    const int x = u + l.pad, y = v + l.pad;
    if (x < 0 || y < 0 || x >= l.width || y >= l.height) return 0;
    return l.cells[static_cast<size_t>(y) * l.width + x];
  }

 private:
  struct Level {
    int pad{0};  // cells below 0 held (a window starting there reaches into the grid)
    int width{0}, height{0};
    std::vector<std::uint8_t> cells;
  };
  double resolution_{0.05};
  Eigen::Vector2d origin_{Eigen::Vector2d::Zero()};  // the corner of cell (0, 0)
  int width_{0}, height_{0};
  Eigen::AlignedBox2i walls_;
  std::vector<Level> pyramid_;
};

}  // namespace matching
}  // namespace is_graphs
