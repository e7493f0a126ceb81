// SGraphBuilder: rooms, corridors and the floor over them.
#include <algorithm>
#include <cmath>

#include "is_graphs/sgraph/corridor_detection.h"
#include "is_graphs/sgraph/room_detection.h"
#include "is_graphs/sgraph/sgraph_builder.h"

namespace is_graphs {
namespace sgraph {

double SGraphBuilder::FloorHeight() const {
  for (const auto& p : planes_)
    if (p.merged_into < 0 && p.horizontal && p.plane.plane.normal.z() > 0.9)
      return p.plane.plane.d / p.plane.plane.normal.z();
  return keyframes_.empty() ? 0.0 : keyframes_.front().pose.translation().z() - 0.5;
}

bool SGraphBuilder::InsideWalls(const std::vector<int>& wall_ids,
                                const Eigen::Vector2d& point) const {
  constexpr double kMargin = 0.3;  // m: a centre may sit this far behind one of the walls
  for (int id : wall_ids) {
    if (id < 0 || id >= static_cast<int>(planes_.size())) continue;
    const geometry::Plane& plane = planes_[id].plane.plane;
    const double horizontal = plane.normal.head<2>().norm();
    if (horizontal < 0.9) continue;
    // Normals point into the room: inside is in front of every wall.
    if ((plane.normal.head<2>().dot(point) - plane.d) / horizontal < -kMargin) return false;
  }
  return true;
}

void SGraphBuilder::UpdateRooms(int keyframe) {
  constexpr double kInView = 0.3;  // m: a room centre in view lies this far short of a wall
  const Eigen::Isometry3d& pose = keyframes_[keyframe].pose;
  const double z = pose.translation().z();
  std::vector<Wall2D> walls;
  for (const auto& p : planes_) {
    if (p.horizontal || p.merged_into >= 0) continue;
    const Eigen::Vector3d& n = p.plane.plane.normal;
    const double horizontal = n.head<2>().norm();
    if (horizontal < 0.9) continue;
    Wall2D w;
    w.id = p.plane.id;
    w.normal = n.head<2>() / horizontal;
    w.d = (p.plane.plane.d - n.z() * z) / horizontal;
    w.start = p.start.head<2>();
    w.end = p.end.head<2>();
    walls.push_back(w);
  }
  const Eigen::Vector2d position = pose.translation().head<2>();
  if (InOpening(walls, position, frontend_)) return;
  const RayFan fan = CastRays(walls, position, frontend_);
  std::optional<RoomCandidate> candidate = DetectRoom(walls, position, fan, frontend_);
  if (!candidate) candidate = DetectCorridor(walls, position, fan, frontend_);
  if (!candidate) return;
  // The same room seen again: shares two walls and lies near; a corridor closed later becomes
  // a room.
  for (size_t r = 0; r < rooms_.size(); ++r) {
    BackendRoom& room = rooms_[r];
    // Shared walls: the same plane, or one on the same line (a face mapped twice before its
    // planes were merged).
    int shared = 0, same_id = 0;
    for (int id : candidate->walls) {
      const bool same = std::count(room.planes.begin(), room.planes.end(), id) > 0;
      const Wall2D* wall = FindWall(walls, id);
      const bool on_line =
          !same && wall && std::any_of(room.planes.begin(), room.planes.end(), [&](int p) {
            const Wall2D* other = FindWall(walls, p);
            return other && SameLine(*wall, *other);
          });
      same_id += same ? 1 : 0;
      shared += same || on_line ? 1 : 0;
    }
    const bool near = (room.center - candidate->center).norm() < 1.5;
    // Or each centre inside the other's walls (one room seen from elsewhere: a corridor's
    // centre moves along it with the robot, a polygonal room's with the visible part of it).
    const bool mutual = shared >= 1 && InsideWalls(room.planes, candidate->center) &&
                        InsideWalls(candidate->walls, room.center);
    const bool seen_before = (shared >= 2 && (near || room.type != candidate->type)) || mutual;
    // Or one space closed at different places (a corridor by the walls of the corridors crossing
    // it): the larger four-wall closure is the space itself.
    const bool same_space =
        !seen_before && shared >= 2 &&
        SameSpace(walls, room.planes, room.center, candidate->walls, candidate->center);
    // Or one nested in the other, sharing three walls: a part of a four-wall room closed off by
    // a partition that leaves a wide passage (the room was accepted with that wall inside it),
    // or a four-wall room and the larger space it opens onto without a wall between (an
    // open-plan hall, kitchen and living room seen from the hall). Inside a polygonal view is
    // inside what the rays saw (its walls need not enclose a convex area).
    const bool nested =
        !seen_before && !same_space && shared >= 3 &&
        (InsideWalls(room.planes, candidate->center) ||
         InsideWalls(candidate->walls, room.center) || InFan(fan, position, room.center, kInView));
    if (!seen_before && !same_space && !nested) continue;
    // A corridor closed later, or a polygonal room (a doorway's far wall counted in) seen
    // later as the four-wall room it is, takes the better view.
    const bool better =
        (room.type == RoomType::kCorridor && candidate->type == RoomType::kRoom) ||
        (room.type == RoomType::kRoom && candidate->rectangular &&
         (!room.rectangular || (seen_before && candidate->share > room.share + 0.05) ||
          (same_space && candidate->area > 1.2 * room.area))) ||
        // Of a nested pair: the four-wall room (above), the larger if both are; of two
        // polygonal rooms, the one less than half the other's area (the larger is that room and
        // what it opens onto).
        (nested && candidate->rectangular && room.rectangular &&
         candidate->area > 1.2 * room.area) ||
        (nested && !candidate->rectangular && !room.rectangular &&
         candidate->area < 0.5 * room.area) ||
        // A polygonal room closed again by fewer of its walls, each wall left out lying behind
        // one kept: it was seen through a doorway (the first view, from just inside it).
        (room.type == RoomType::kRoom && !room.rectangular && seen_before &&
         same_id == static_cast<int>(candidate->walls.size()) &&
         candidate->walls.size() < room.planes.size() &&
         LeftOutLieBehind(walls, room.planes, candidate->walls));
    if (better) {
      room.type = RoomType::kRoom;
      room.rectangular = candidate->rectangular;
      room.share = candidate->share;
      room.area = candidate->area;
      room.center = candidate->center;
      room.initial_center = candidate->center;
      room.planes = candidate->walls;
      room.distances = candidate->distances;
    }
    room_keyframes_[r].push_back(keyframe);
    return;
  }
  BackendRoom room;
  room.id = static_cast<int>(rooms_.size());
  room.type = candidate->type;
  room.center = candidate->center;
  room.initial_center = candidate->center;
  room.z = FloorHeight();
  room.planes = candidate->walls;
  room.distances = candidate->distances;
  room.axis = candidate->axis;
  room.rectangular = candidate->rectangular;
  room.share = candidate->share;
  room.area = candidate->area;
  rooms_.push_back(room);
  room_keyframes_.push_back({keyframe});
  UpdateFloor();
}

void SGraphBuilder::UpdateFloor() {
  if (rooms_.empty()) return;
  floor_.present = true;
  floor_.center = Eigen::Vector2d::Zero();
  floor_.rooms.clear();
  floor_.offsets.clear();
  for (const auto& r : rooms_) floor_.center += r.center;
  floor_.center /= static_cast<double>(rooms_.size());
  for (const auto& r : rooms_) {
    floor_.rooms.push_back(r.id);
    floor_.offsets.push_back(r.center - floor_.center);
  }
}

}  // namespace sgraph
}  // namespace is_graphs
