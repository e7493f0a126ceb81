#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "is_graphs/geometry/plane.h"

namespace is_graphs {
namespace sgraph {

// The Situational Graph in the map frame M, as the S-Graph node publishes it (msg/SGraph.msg).
// Ids are stable across revisions but not necessarily dense (planes can be merged away);
// references between elements use ids, not vector indices.

struct Keyframe {
  int id{0};
  double stamp{0.0};                                               // seconds
  Eigen::Isometry3d pose{Eigen::Isometry3d::Identity()};           // optimized, map <- base_link
  Eigen::Isometry3d odom_pose{Eigen::Isometry3d::Identity()};      // measured, odom <- base_link
  int previous{-1};                                                // id, -1 for the first keyframe
  Eigen::Isometry3d relative_odom{Eigen::Isometry3d::Identity()};  // previous^-1 * this
  Eigen::Matrix<double, 6, 6> odom_information{Eigen::Matrix<double, 6, 6>::Identity()};
  int level{0};      // the storey walked (levels.h): 0 until a stair climb reaches another
  double path{0.0};  // m of odometry path walked from the first keyframe to this one
  // Its scan's points in a horizontal band (FrontendConfig slice_*), in base_link; only the
  // newest slice_keyframes keyframes carry them (the others: empty).
  std::vector<Eigen::Vector3f> slice;
};

struct Plane {
  int id{0};
  geometry::Plane plane;  // in M; normal points to the side the sensor saw it from
  geometry::Orientation orientation{geometry::Orientation::kOther};
  Eigen::Matrix4d covariance{Eigen::Matrix4d::Identity()};  // of (nx, ny, nz, d)
  Eigen::Vector2d start{Eigen::Vector2d::Zero()};           // horizontal extent on the plane
  Eigen::Vector2d end{Eigen::Vector2d::Zero()};
  double z_min{0.0};
  double z_max{0.0};
  int num_points{0};
};

/// A keyframe's observation of a plane, in the keyframe's base_link frame.
struct PlaneObservation {
  int keyframe{0};
  int plane{0};
  geometry::Plane local;
  Eigen::Matrix3d information{Eigen::Matrix3d::Identity()};  // on the plane's minimal tangent
};

enum class RoomType { kRoom = 0, kCorridor = 1 };

struct Room {
  int id{0};
  RoomType type{RoomType::kRoom};
  Eigen::Vector3d center{Eigen::Vector3d::Zero()};
  std::vector<int> planes;     // plane ids
  std::vector<int> keyframes;  // keyframe ids taken inside it
  // On the centre as a stand-in for the room's true centre (0.1 m unless set; a polygonal room's
  // is looser, BackendConfig::polygon_room_sigma).
  Eigen::Matrix3d information{Eigen::Matrix3d::Identity() * 100.0};
};

struct Floor {
  int id{0};
  Eigen::Vector3d center{Eigen::Vector3d::Zero()};
  double height{0.0};
  std::vector<int> rooms;  // room ids
};

/// A doorway the robot walked through: where a keyframe step crossed wall planes (a wall's two
/// faces, or the gap between two collinear pieces of one), in M. msg/SDoorway.msg.
struct Doorway {
  int id{0};  // 16 x the keyframe before its first crossing + its rank in that step: stable
  Eigen::Vector3d position{Eigen::Vector3d::Zero()};  // mean crossing point, at floor height
  double width{0.0};           // m, from the gap in the wall; 0 when the gap was not closed
  std::vector<int> rooms;      // S-room ids on its sides (those owning a crossed plane)
  std::vector<int> planes;     // the crossed wall planes (the wall's faces or pieces)
  std::vector<int> keyframes;  // the keyframes before each crossing step
};

struct SGraph {
  unsigned revision{0};
  double stamp{0.0};
  std::vector<Keyframe> keyframes;
  std::vector<Plane> planes;
  std::vector<PlaneObservation> observations;
  std::vector<Room> rooms;
  std::vector<Floor> floors;
  std::vector<Doorway> doorways;
  double odometry_scale{1.0};  // the back end's estimate of the odometry's distance scale
};

}  // namespace sgraph
}  // namespace is_graphs
