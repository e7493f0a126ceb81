#pragma once

#include <ceres/problem.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "is_graphs/agraph/agraph.h"

namespace is_graphs {
namespace agraph {

struct AGraphProblemConfig {
  double plane_angle_sigma{0.01};   // rad: surface normal prior (PlanePriorCost)
  double plane_offset_sigma{0.01};  // m: surface offset prior (PlanePriorCost)
  double wall_centre_sigma{0.01};   // m: wall centre vs. its two faces (WallCentreCost)
  double doorway_sigma{0.05};       // m: room centre − doorway offset (DoorwayRoomCost)
  double room_centre_sigma{0.05};   // m: room centre prior (PointPriorCost)
  double huber_scale{1.0};          // Huber loss on the whitened residuals, in σ; 0: none
  int max_iterations{100};
  int num_threads{1};

  /// "" when valid, else what is wrong, naming the parameter.
  std::string Validate() const;
};

struct AGraphSolveSummary {
  bool usable{false};  // ceres' Summary::IsSolutionUsable()
  double initial_cost{0.0};
  double final_cost{0.0};
  int iterations{0};
  double time_s{0.0};
  int residual_blocks{0};
  int parameter_blocks{0};
  std::string termination;  // ceres' message

  std::string ToString() const;
};

/// The A-Graph as a Ceres least-squares problem, in the BIM frame. Owns the parameter blocks,
/// initialized from the graph:
///   per wall surface  normal[3] (on ceres::SphereManifold<3>), d[1]
///   per wall          centre[3]
///   per room          centre[3]
///   per doorway       position[3]
/// and adds them with their factors to any ceres::Problem (AddTo), so that the merger can put
/// the A-Graph into a larger problem: a plane prior per surface, a wall-centre factor per wall,
/// a doorway–room factor per doorway and connected room, a prior per room centre.
/// The graph must be valid (ValidateAGraph; LoadAGraph guarantees it), the config too.
class AGraphProblem {
 public:
  explicit AGraphProblem(const AGraph& graph, const AGraphProblemConfig& config = {});
  // The blocks' addresses are handed to ceres: not copyable nor movable.
  AGraphProblem(const AGraphProblem&) = delete;
  AGraphProblem& operator=(const AGraphProblem&) = delete;

  /// Adds the parameter blocks, manifolds, loss and factors. `problem` must own cost
  /// functions, losses and manifolds (the default ceres::Problem::Options) and must not
  /// outlive this object.
  void AddTo(ceres::Problem& problem);

  /// As AddTo, but only the parts of the A-Graph's factor graph that hold one of these
  /// wall-surfaces or rooms (ids; others ignored): a surface with its wall, the wall's other face
  /// and their priors; a room with its doorways and, through them, the rooms they lead to. The
  /// parts left out share no factor with those added, so the estimates of the parts added are
  /// what AddTo would give them; the merger, whose matches touch a few walls and rooms of a
  /// building, solves a problem the size of what it matched instead of the whole A-Graph.
  void AddConnectedTo(ceres::Problem& problem, const std::vector<int>& surfaces,
                      const std::vector<int>& rooms);

  /// Builds a problem of the A-Graph alone and solves it (SPARSE_NORMAL_CHOLESKY, SuiteSparse
  /// when ceres has it, else Eigen's sparse Cholesky).
  AGraphSolveSummary Solve();

  /// Copies the current estimates into `graph` (which must have this graph's element counts):
  /// surface planes, wall centres, room centres, doorway positions. False on a count mismatch.
  bool WriteBack(AGraph& graph) const;

  double* SurfaceNormal(int surface) { return normals_[surface].data(); }
  double* SurfaceOffset(int surface) { return &offsets_[surface]; }
  double* WallCentre(int wall) { return wall_centres_[wall].data(); }
  double* RoomCentre(int room) { return room_centres_[room].data(); }
  double* DoorwayPosition(int doorway) { return doorway_positions_[doorway].data(); }

  const AGraph& measured() const { return measured_; }
  const AGraphProblemConfig& config() const { return config_; }

 private:
  void AddParts(ceres::Problem& problem, const std::vector<bool>& surfaces,
                const std::vector<bool>& rooms);

  AGraph measured_;
  AGraphProblemConfig config_;
  // Sized once in the constructor: the addresses of their elements never change.
  std::vector<Eigen::Vector3d> normals_;
  std::vector<double> offsets_;
  std::vector<Eigen::Vector3d> wall_centres_;
  std::vector<Eigen::Vector3d> room_centres_;
  std::vector<Eigen::Vector3d> doorway_positions_;
};

}  // namespace agraph
}  // namespace is_graphs
