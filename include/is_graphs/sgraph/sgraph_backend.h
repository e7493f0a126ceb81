#pragma once

#include <Eigen/Core>
#include <set>
#include <string>
#include <vector>

#include "is_graphs/sgraph/backend_config.h"
#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace sgraph {

/// A room's or corridor's factors as the back end needs them.
struct BackendRoom {
  int id{0};
  RoomType type{RoomType::kRoom};
  Eigen::Vector2d center{Eigen::Vector2d::Zero()};  // estimate, written back
  double z{0.0};
  std::vector<int> planes;        // plane ids
  std::vector<double> distances;  // measured signed distance centre -> plane, per plane
  Eigen::Vector2d axis{Eigen::Vector2d::UnitX()};  // corridors
  Eigen::Vector2d initial_center{Eigen::Vector2d::Zero()};
  // Front end only: a four-wall room, and the share of rays its walls took (a better view of
  // the same room, or a polygonal room seen later as four walls, replaces its walls).
  bool rectangular{false};
  double share{0.0};
  double area{0.0};  // m², of the visibility polygon that closed it
};

struct BackendFloor {
  bool present{false};
  Eigen::Vector2d center{Eigen::Vector2d::Zero()};
  std::vector<int> rooms;                // room ids
  std::vector<Eigen::Vector2d> offsets;  // measured room centre − floor centre, per room
};

/// Everything the optimization reads and writes (a copy of the builder's state).
struct BackendProblem {
  std::vector<Keyframe> keyframes;  // poses written back
  std::vector<Plane> planes;        // plane (n, d) written back
  std::vector<PlaneObservation> observations;
  std::vector<BackendRoom> rooms;
  BackendFloor floor;
  double odometry_scale{1.0};  // odometry distance scale factor: initial value, written back
  // Windowed (SelectWindow, backend_window.h): ids of what enters held at its value. Keyframes
  // and observations are then only the window's part; planes, rooms and the floor all of them
  // (a plane, room or floor centre neither moved nor held has no factor and stays out).
  std::set<int> constant_keyframes, constant_planes, constant_rooms;
  bool constant_floor{false};
};

struct BackendSummary {
  bool usable{false};
  double initial_cost{0.0};
  double final_cost{0.0};
  int iterations{0};
  double seconds{0.0};
  int num_keyframes{0};           // in the problem (moved or held)
  int num_variable_keyframes{0};  // of them, moved
  int num_residual_blocks{0};
  std::string message;
};

/// Solves the S-Graph with Ceres (SPARSE_NORMAL_CHOLESKY on SuiteSparse): keyframe poses on
/// EigenQuaternionManifold, plane normals on SphereManifold<3>, room/corridor/floor centres
/// in the plane. Factors: odometry (odometry_cost.h), keyframe–plane (Huber), room–plane and
/// corridor–plane (Cauchy), floor–room. The first keyframe is held fixed (the gauge).
/// Results are written back into `problem`.
BackendSummary OptimizeSGraph(BackendProblem& problem, const BackendConfig& config);

}  // namespace sgraph
}  // namespace is_graphs
