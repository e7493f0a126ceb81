#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "is_graphs/sgraph/frontend_config.h"
#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace sgraph {

/// A mapped wall seen from above: the line n·x = d (n horizontal, unit, into the room it was
/// seen from) and the extent [start, end] of its points.
struct Wall2D {
  int id{0};
  Eigen::Vector2d normal{Eigen::Vector2d::UnitX()};
  double d{0.0};
  Eigen::Vector2d start{Eigen::Vector2d::Zero()};
  Eigen::Vector2d end{Eigen::Vector2d::Zero()};
};

/// A room or corridor found around a keyframe.
struct RoomCandidate {
  RoomType type{RoomType::kRoom};
  bool rectangular{false};  // the paper's four-wall room (two opposed pairs)
  double share{0.0};        // of the rays ending on its four walls (rectangular rooms)
  double area{0.0};         // m², of the visibility polygon (the closed space seen)
  Eigen::Vector2d center{Eigen::Vector2d::Zero()};
  std::vector<int> walls;         // Wall2D ids
  std::vector<double> distances;  // n·center − d per wall (> 0: the centre is in front)
  Eigen::Vector2d axis{Eigen::Vector2d::Zero()};  // corridors: the direction along it
};

/// Whether `position` lies in an opening of a mapped wall: within `room_opening_band` of the
/// wall's line, where its seen extent (grown by `room_gap_margin`) runs. Standing in a doorway
/// or a corridor's mouth the robot sees two spaces at once, and their union is no room.
bool InOpening(const std::vector<Wall2D>& walls, const Eigen::Vector2d& position,
               const FrontendConfig& config);

/// Whether two walls lie on one line, facing the same way (pieces of one wall face, or one
/// face mapped twice before the planes were merged): normals within 3°, offsets within 0.1 m.
bool SameLine(const Wall2D& a, const Wall2D& b);

/// Whether `behind` is seen through an opening of `front`: facing the same way, parallel, set
/// back behind it by 0.1-0.6 m, in a wall's depth (a window's pane or reveal, a door leaf in its
/// frame, an alcove), and not a wall `front` merely stands before (a cupboard's front whose
/// whole seen extent lies along the wall behind it).
bool SeenThroughOpening(const Wall2D& front, const Wall2D& behind);

/// The wall with that id, nullptr if none.
const Wall2D* FindWall(const std::vector<Wall2D>& walls, int id);

/// Whether every wall in `all` but not in `kept` (ids into `walls`) lies wholly behind the line
/// of a wall in `kept`, i.e. was seen beyond it through an opening. False when an id is unknown.
bool LeftOutLieBehind(const std::vector<Wall2D>& walls, const std::vector<int>& all,
                      const std::vector<int>& kept);

/// Rays cast horizontally from a position against the walls facing it; each wall is extended
/// by `room_gap_margin` at both ends (doorways, unseen corners).
struct RayFan {
  std::vector<Eigen::Vector2d> directions;
  std::vector<int> hit;  // index into the walls, −1: nothing within room_max_range
  std::vector<double> range;
  std::vector<char> on_extent;  // 1: the hit lies on the wall's seen extent (not a slack/margin)
};

RayFan CastRays(const std::vector<Wall2D>& walls, const Eigen::Vector2d& position,
                const FrontendConfig& config);

/// Whether `point` lies inside the fan's visibility polygon (cast from `position`): nearer than
/// the wall its ray ends on, less `margin`. A ray that ends on nothing sees everything.
bool InFan(const RayFan& fan, const Eigen::Vector2d& position, const Eigen::Vector2d& point,
           double margin);

/// How many rays of the fan hit each wall (indexed like the walls).
std::vector<int> CountHits(const RayFan& fan, size_t num_walls);

/// A closed room around `position`: (almost) every ray hits a wall that faces it and covers a
/// noticeable sector (stray hits through doorways do not count), and that is seen bounding this
/// space: a wall hit only on its corner slack or doorway margins (an office's side wall whose
/// margin crosses a corridor) closes nothing. Two opposed pairs of walls
/// make the paper's four-wall room, centred where the pairs' mid-lines cross; three or more
/// walls in another arrangement (L-shaped, trapezoid) a polygonal room, centred on the area
/// centroid of the visibility polygon. nullopt when not closed or out of the size limits.
std::optional<RoomCandidate> DetectRoom(const std::vector<Wall2D>& walls,
                                        const Eigen::Vector2d& position, const RayFan& fan,
                                        const FrontendConfig& config);

/// Whether two room detections (wall ids into `walls`, centres) are one space seen from two
/// places: they share two opposed walls with both centres between them (0.3 m slack), and no
/// wall's seen extent lies across the segment joining the centres. A corridor closed at
/// different places by the walls of rooms and corridors seen through its doorways is one space;
/// two offices along one corridor wall and one façade are not (a partition lies between).
bool SameSpace(const std::vector<Wall2D>& walls, const std::vector<int>& a_walls,
               const Eigen::Vector2d& a_center, const std::vector<int>& b_walls,
               const Eigen::Vector2d& b_center);

}  // namespace sgraph
}  // namespace is_graphs
