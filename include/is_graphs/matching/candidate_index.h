#pragma once

#include <Eigen/Core>
#include <vector>

#include "is_graphs/matching/candidate_graph.h"
#include "is_graphs/matching/room_descriptor.h"

namespace is_graphs {
namespace matching {

/// The local candidates of each S-room, found by where their A-room's centre lies. Growing a
/// hypothesis from a seed pair, an S-room can only join through a candidate whose A-room centre
/// is near where the seed's motion puts the S-room's centre (RoomPairConsistency); asking this
/// index for those instead of scanning every candidate makes a grow cost the rooms near the
/// prediction, not the whole building. Answers keep the list order, so that ties between equal
/// candidates break as in a full scan; candidates free along a corridor's axis (not full-rank),
/// whose centre says little, are always in the answer.
class CandidateIndex {
 public:
  /// `candidates[i]` are S-room i's candidates against `a_rooms` (which must outlive the index).
  /// The grid's cells are `cell` metres, larger where the A-rooms spread over more than
  /// kMaxCells cells a side (a stray room centre far off must not allocate a huge grid).
  CandidateIndex(const std::vector<std::vector<RoomCandidate>>& candidates,
                 const std::vector<RoomDescriptor>& a_rooms, double cell = 2.0);

  /// Indices into candidates[s_room], ascending: every full-rank one whose A-room centre lies
  /// within `radius` of `centre`, and every axis-free one.
  void Near(int s_room, const Eigen::Vector2d& centre, double radius, std::vector<int>* out) const;

 private:
  static constexpr int kMaxCells = 512;
  /// The grid cell of point p, -1 beyond the grid.
  int CellOf(const Eigen::Vector2d& p) const;
  // A-room centres on a grid (CSR: the rooms of cell c are rooms_in_cell_[cell_start_[c] ..]).
  double cell_;
  Eigen::Vector2d origin_{Eigen::Vector2d::Zero()};
  int nx_{0}, ny_{0};
  std::vector<int> cell_start_, rooms_in_cell_;
  const std::vector<RoomDescriptor>* a_rooms_;
  // Per S-room: its full-rank candidates by A-room (CSR over A-rooms), the axis-free ones.
  struct Room {
    std::vector<int> a_start, by_a;
    std::vector<int> always;
    // The centre_off ones (their A-centre is not where their S-centre goes), by that point:
    // on the grid (CSR over cells), and those beyond it in a list.
    std::vector<int> off_start;
    std::vector<std::pair<int, Eigen::Vector2d>> off_in_cell, off_beyond;
    int size{0};
  };
  std::vector<Room> rooms_;
};

/// The radius around the predicted A-centre within which RoomPairConsistency can accept a room
/// pair whose S-centre lies `s_distance` from the seed's: the test allows 2·centre_tolerance
/// plus lever_arm_slack per metre between the A-centres, which are at most the radius farther
/// apart than the S-centres. Infinite when lever_arm_slack >= 1.
double ConsistencyRadius(double s_distance, double centre_tolerance, double lever_arm_slack);

}  // namespace matching
}  // namespace is_graphs
