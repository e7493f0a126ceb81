#include "is_graphs/matching/candidate_index.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace is_graphs {
namespace matching {
namespace {

/// Compressed rows: the items of row r are items[start[r] .. start[r + 1]).
void Compress(const std::vector<int>& row_of, int rows, std::vector<int>* start,
              std::vector<int>* items) {
  start->assign(rows + 1, 0);
  for (int r : row_of) ++(*start)[r + 1];
  for (int r = 0; r < rows; ++r) (*start)[r + 1] += (*start)[r];
  items->assign(row_of.size(), 0);
  std::vector<int> next(start->begin(), start->end() - 1);
  for (size_t i = 0; i < row_of.size(); ++i) (*items)[next[row_of[i]]++] = static_cast<int>(i);
}

}  // namespace

CandidateIndex::CandidateIndex(const std::vector<std::vector<RoomCandidate>>& candidates,
                               const std::vector<RoomDescriptor>& a_rooms, double cell)
    : cell_(cell), a_rooms_(&a_rooms), rooms_(candidates.size()) {
  Eigen::Vector2d hi = Eigen::Vector2d::Constant(-std::numeric_limits<double>::infinity());
  origin_ = -hi;
  for (const auto& a : a_rooms) origin_ = origin_.cwiseMin(a.centre), hi = hi.cwiseMax(a.centre);
  if (a_rooms.empty()) origin_ = hi = Eigen::Vector2d::Zero();
  cell_ = std::max(cell_, (hi - origin_).maxCoeff() / kMaxCells);
  nx_ = static_cast<int>((hi.x() - origin_.x()) / cell_) + 1;
  ny_ = static_cast<int>((hi.y() - origin_.y()) / cell_) + 1;
  std::vector<int> cell_of(a_rooms.size());
  for (size_t i = 0; i < a_rooms.size(); ++i) {
    const Eigen::Vector2d g = (a_rooms[i].centre - origin_) / cell_;
    cell_of[i] = std::min(static_cast<int>(g.y()), ny_ - 1) * nx_ +
                 std::min(static_cast<int>(g.x()), nx_ - 1);
  }
  Compress(cell_of, nx_ * ny_, &cell_start_, &rooms_in_cell_);

  for (size_t i = 0; i < candidates.size(); ++i) {
    Room& room = rooms_[i];
    room.size = static_cast<int>(candidates[i].size());
    std::vector<int> a_of;  // of the full-rank ones, in list order
    std::vector<int> full;
    std::vector<int> off_cell, off;  // of the centre_off ones on the grid
    for (int k = 0; k < room.size; ++k) {
      const RoomCandidate& c = candidates[i][k];
      if (c.full_rank && c.centre_off) {
        const int cell_of_at = CellOf(c.at);
        if (cell_of_at < 0)
          room.off_beyond.emplace_back(k, c.at);
        else
          off_cell.push_back(cell_of_at), off.push_back(k);
      } else if (c.full_rank) {
        a_of.push_back(c.a_room), full.push_back(k);
      } else {
        room.always.push_back(k);
      }
    }
    Compress(a_of, static_cast<int>(a_rooms.size()), &room.a_start, &room.by_a);
    for (int& k : room.by_a) k = full[k];
    if (off.empty()) continue;  // no cells for none (most S-rooms)
    std::vector<int> order;
    Compress(off_cell, nx_ * ny_, &room.off_start, &order);
    for (int k : order) room.off_in_cell.emplace_back(off[k], candidates[i][off[k]].at);
  }
}

int CandidateIndex::CellOf(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d g = (p - origin_) / cell_;
  if (!g.allFinite()) return -1;
  const double x = std::floor(g.x()), y = std::floor(g.y());
  if (x < 0.0 || y < 0.0 || x >= nx_ || y >= ny_) return -1;
  return static_cast<int>(y) * nx_ + static_cast<int>(x);
}

void CandidateIndex::Near(int s_room, const Eigen::Vector2d& centre, double radius,
                          std::vector<int>* out) const {
  out->clear();
  const Room& room = rooms_[s_room];
  const double span = std::ceil(2.0 * radius / cell_) + 1.0;
  if (!std::isfinite(radius) || !centre.allFinite() || span * span >= room.size) {
    // As many cells as candidates: a scan is cheaper (and covers an unbounded radius).
    out->resize(room.size);
    for (int k = 0; k < room.size; ++k) (*out)[k] = k;
    return;
  }
  *out = room.always;
  for (const auto& [k, at] : room.off_beyond)
    if ((at - centre).norm() <= radius) out->push_back(k);
  const Eigen::Vector2d lo = (centre - origin_).array() / cell_ - radius / cell_;
  const Eigen::Vector2d hi = (centre - origin_).array() / cell_ + radius / cell_;
  const int x0 = std::max(0, static_cast<int>(std::floor(lo.x())));
  const int y0 = std::max(0, static_cast<int>(std::floor(lo.y())));
  const int x1 = std::min(nx_ - 1, static_cast<int>(std::floor(hi.x())));
  const int y1 = std::min(ny_ - 1, static_cast<int>(std::floor(hi.y())));
  const bool off = !room.off_start.empty();
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const int c = y * nx_ + x;
      for (int j = off ? room.off_start[c] : 0; off && j < room.off_start[c + 1]; ++j) {
        const auto& [k, at] = room.off_in_cell[j];
        if ((at - centre).norm() <= radius) out->push_back(k);
      }
      for (int j = cell_start_[c]; j < cell_start_[c + 1]; ++j) {
        const int a = rooms_in_cell_[j];
        if (room.a_start[a] == room.a_start[a + 1]) continue;
        if (((*a_rooms_)[a].centre - centre).norm() > radius) continue;
        out->insert(out->end(), room.by_a.begin() + room.a_start[a],
                    room.by_a.begin() + room.a_start[a + 1]);
      }
    }
  std::sort(out->begin(), out->end());
}

double ConsistencyRadius(double s_distance, double centre_tolerance, double lever_arm_slack) {
  if (lever_arm_slack >= 1.0) return std::numeric_limits<double>::infinity();
  const double r =
      (2.0 * centre_tolerance + lever_arm_slack * s_distance) / (1.0 - lever_arm_slack);
  return r * (1.0 + 1e-9) + 1e-9;  // a superset of what the test accepts, rounding included
}

}  // namespace matching
}  // namespace is_graphs
