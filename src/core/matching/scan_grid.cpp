#include "is_graphs/matching/scan_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "is_graphs/geometry/se3.h"

namespace is_graphs {
namespace matching {

namespace {

double SquaredDistanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                                const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + s * ab - p).squaredNorm();
}

int FloorDiv(double v, double r) { return static_cast<int>(std::floor(v / r)); }

constexpr int kChunk = 32;     // points between the checks of a bound against its threshold
constexpr size_t kSpread = 8;  // every kSpread-th point comes first (Thin)

}  // namespace

ScanGrid::ScanGrid(const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& segments,
                   double resolution, double sigma, int levels)
    : resolution_(resolution) {
  const double r = resolution;
  const double cutoff = 6.0 * sigma;  // beyond it the score is below 1.6e-8: 0
  Eigen::Vector2d lo = segments.front().first, hi = lo;
  for (const auto& [a, b] : segments) {
    lo = lo.cwiseMin(a).cwiseMin(b);
    hi = hi.cwiseMax(a).cwiseMax(b);
  }
  walls_min_ = {FloorDiv(lo.x(), r), FloorDiv(lo.y(), r)};
  walls_max_ = {FloorDiv(hi.x(), r), FloorDiv(hi.y(), r)};
  // Below the walls, room for the pooled windows that start there and reach them.
  const int pad = static_cast<int>(std::ceil(cutoff / r)) + 1;
  const int low = pad + (1 << (levels - 1));
  origin_ = walls_min_ - Eigen::Vector2i::Constant(low);
  size_ = walls_max_ + Eigen::Vector2i::Constant(pad + 1) - origin_;
  const size_t n = static_cast<size_t>(size_.x()) * size_.y();

  // The exact distance per cell centre to the segments within the cutoff.
  std::vector<float> d2(n, static_cast<float>(cutoff * cutoff));
  for (const auto& [a, b] : segments) {
    const int i0 = FloorDiv(std::min(a.x(), b.x()) - cutoff, r) - origin_.x();
    const int i1 = FloorDiv(std::max(a.x(), b.x()) + cutoff, r) - origin_.x();
    const int j0 = FloorDiv(std::min(a.y(), b.y()) - cutoff, r) - origin_.y();
    const int j1 = FloorDiv(std::max(a.y(), b.y()) + cutoff, r) - origin_.y();
    for (int j = std::max(j0, 0); j <= std::min(j1, size_.y() - 1); ++j)
      for (int i = std::max(i0, 0); i <= std::min(i1, size_.x() - 1); ++i) {
        const Eigen::Vector2d c((i + origin_.x() + 0.5) * r, (j + origin_.y() + 0.5) * r);
        float& cell = d2[static_cast<size_t>(j) * size_.x() + i];
        cell = std::min(cell, static_cast<float>(SquaredDistanceToSegment(c, a, b)));
      }
  }
  pyramid_.assign(levels, std::vector<float>(n, 0.0f));
  const float limit = static_cast<float>(cutoff * cutoff);
  for (size_t k = 0; k < n; ++k)
    if (d2[k] < limit) pyramid_[0][k] = static_cast<float>(std::exp(-d2[k] / (2 * sigma * sigma)));

  // Level h: the max of four windows of level h-1 (x then y), past the grid's end 0.
  std::vector<float> tmp(n);
  for (int h = 1; h < levels; ++h) {
    const int s = 1 << (h - 1);
    const std::vector<float>& prev = pyramid_[h - 1];
    for (int j = 0; j < size_.y(); ++j) {
      const float* row = &prev[static_cast<size_t>(j) * size_.x()];
      float* out = &tmp[static_cast<size_t>(j) * size_.x()];
      for (int i = 0; i < size_.x(); ++i)
        out[i] = i + s < size_.x() ? std::max(row[i], row[i + s]) : row[i];
    }
    std::vector<float>& cur = pyramid_[h];
    for (int j = 0; j < size_.y(); ++j) {
      const float* a = &tmp[static_cast<size_t>(j) * size_.x()];
      float* out = &cur[static_cast<size_t>(j) * size_.x()];
      if (j + s < size_.y()) {
        const float* b = &tmp[static_cast<size_t>(j + s) * size_.x()];
        for (int i = 0; i < size_.x(); ++i) out[i] = std::max(a[i], b[i]);
      } else {
        std::copy(a, a + size_.x(), out);
      }
    }
  }
}

Eigen::Vector2i ScanGrid::CellOf(const Eigen::Vector2d& p) const {
  return {FloorDiv(p.x(), resolution_), FloorDiv(p.y(), resolution_)};
}

std::vector<Eigen::Vector2d> ScanProblem::Thin(const std::vector<Eigen::Vector2d>& points,
                                               double resolution) {
  std::vector<std::tuple<long long, long long, size_t>> keys;
  keys.reserve(points.size());
  for (size_t k = 0; k < points.size(); ++k)
    if (points[k].allFinite())
      keys.emplace_back(static_cast<long long>(std::floor(points[k].x() / resolution)),
                        static_cast<long long>(std::floor(points[k].y() / resolution)), k);
  std::sort(keys.begin(), keys.end());
  std::vector<Eigen::Vector2d> thinned;
  for (size_t k = 0; k < keys.size();) {
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    size_t e = k;
    for (; e < keys.size() && std::get<0>(keys[e]) == std::get<0>(keys[k]) &&
           std::get<1>(keys[e]) == std::get<1>(keys[k]);
         ++e)
      sum += points[std::get<2>(keys[e])];
    thinned.push_back(sum / static_cast<double>(e - k));
    k = e;
  }
  // A sample spread over the slice first (every kSpread-th cell), then the rest in cell order:
  // neighbours in a row, for the cache.
  std::vector<Eigen::Vector2d> ordered;
  ordered.reserve(thinned.size());
  for (size_t k = 0; k < thinned.size(); k += kSpread) ordered.push_back(thinned[k]);
  for (size_t k = 0; k < thinned.size(); ++k)
    if (k % kSpread != 0) ordered.push_back(thinned[k]);
  return ordered;
}

ScanProblem::ScanProblem(const ScanGrid& grid, const std::vector<Eigen::Vector2d>& points,
                         double yaw_step)
    : grid_(grid), points_(Thin(points, grid.resolution())) {
  const double r = grid.resolution();
  for (const auto& p : points_) centroid_ += p;
  if (!points_.empty()) centroid_ /= static_cast<double>(points_.size());
  double reach = r;
  for (const auto& p : points_) reach = std::max(reach, (p - centroid_).norm());
  // The farthest point moves about one cell per step (Cartographer's acos(1 - r²/2d²) ≈ r/d).
  const double step = yaw_step > 0.0 ? yaw_step : r / reach;
  yaw_steps_ = std::max(1, static_cast<int>(std::ceil(2.0 * M_PI / step - 1e-9)));
  yaw_step_ = 2.0 * M_PI / yaw_steps_;

  // How far a point may move from its place at an interval's middle yaw over the interval
  // (a chord is shorter than its arc), with a little slack against rounding; the cells it visits
  // per axis then span at most floor(2 rho / r) + 2 (1 when it does not move).
  auto rho = [&](int g) { return reach * ((1 << g) - 1) * 0.5 * yaw_step_ * (1 + 1e-9) + 1e-12; };
  auto span = [&](int g) { return g == 0 ? 1 : static_cast<int>(std::floor(2 * rho(g) / r)) + 2; };
  // Per node level l (translation window 2^l): the widest yaw interval whose cells, with the
  // window's, still fit in the pyramid window of level l + 1 (or l when the yaw is one step).
  const int max_level = grid.levels() - 2;
  yaw_level_ = {0};
  pool_level_ = {0};
  for (int l = 1; l <= max_level; ++l) {
    int g = yaw_level_.back();
    while (g < l && (1 << g) < yaw_steps_ && (1 << l) - 1 + span(g + 1) <= (2 << l)) ++g;
    const int width = (1 << l) - 1 + span(g);
    int h = 0;
    while ((1 << h) < width) ++h;
    yaw_level_.push_back(g);
    pool_level_.push_back(h);
  }

  rotated_.resize(yaw_level_.back() + 1);
  for (int g = 0; g <= yaw_level_.back(); ++g) {
    const int n = (yaw_steps_ + (1 << g) - 1) >> g;
    const double rg = g == 0 ? 0.0 : rho(g);
    rotated_[g].resize(n);
    for (int j = 0; j < n; ++j) {
      const double mid = ((j << g) + 0.5 * ((1 << g) - 1)) * yaw_step_;
      const Eigen::Matrix2d R = Eigen::Rotation2Dd(mid).toRotationMatrix();
      Rotated& out = rotated_[g][j];
      out.x.resize(points_.size());
      out.y.resize(points_.size());
      out.min = Eigen::Vector2i::Constant(std::numeric_limits<int>::max());
      out.max = Eigen::Vector2i::Constant(std::numeric_limits<int>::min());
      for (size_t i = 0; i < points_.size(); ++i) {
        const Eigen::Vector2d u = R * (points_[i] - centroid_);
        out.x[i] = FloorDiv(u.x() - rg, r);
        out.y[i] = FloorDiv(u.y() - rg, r);
        out.min = out.min.cwiseMin(Eigen::Vector2i(out.x[i], out.y[i]));
        out.max = out.max.cwiseMax(Eigen::Vector2i(out.x[i], out.y[i]));
      }
    }
  }
}

double ScanProblem::Bound(const Node& node, double threshold) const {
  if (points_.empty()) return 0.0;
  const int g = yaw_level_[node.level], h = pool_level_[node.level];
  const Rotated& rot = rotated_[g][node.yaw >> g];
  const int n = static_cast<int>(points_.size());
  const Eigen::Vector2i o(node.x - grid_.origin().x(), node.y - grid_.origin().y());
  double sum = 0.0;
  if (rot.min.x() + o.x() >= 0 && rot.min.y() + o.y() >= 0 &&
      rot.max.x() + o.x() < grid_.size().x() && rot.max.y() + o.y() < grid_.size().y()) {
    // Every point inside the grid: no checks in the loop.
    const float* level = grid_.level(h);
    const long stride = grid_.size().x();
    const long base = o.y() * stride + o.x();
    const int* xs = rot.x.data();
    const int* ys = rot.y.data();
    // In chunks: after each, the rest can add at most 1 per point.
    const double need = threshold * n;
    for (int i0 = 0; i0 < n; i0 += kChunk) {
      const int i1 = std::min(n, i0 + kChunk);
      for (int i = i0; i < i1; ++i) sum += level[base + ys[i] * stride + xs[i]];
      if (sum + (n - i1) < need) return (sum + (n - i1)) / n;
    }
  } else {
    for (int i = 0; i < n; ++i) sum += grid_.At(h, rot.x[i] + node.x, rot.y[i] + node.y);
  }
  return sum / n;
}

Pose2 ScanProblem::LeafPose(int x, int y, int yaw) const {
  Pose2 pose;
  pose.yaw = geometry::NormalizeAngle(yaw * yaw_step_);
  const double r = grid_.resolution();
  pose.t = Eigen::Vector2d(x * r, y * r) - pose.R() * centroid_;
  return pose;
}

}  // namespace matching
}  // namespace is_graphs
