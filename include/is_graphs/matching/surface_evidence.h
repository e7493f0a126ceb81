#pragma once

#include <Eigen/Core>
#include <unordered_map>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/matching/matcher_config.h"
#include "is_graphs/matching/rigid_fit.h"
#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace matching {

/// A wall-grade S-plane as a segment in M: where its mapped points lie, the side it was seen
/// from.
struct WallSegment {
  int id{0};  // S-plane id
  Eigen::Vector2d a{Eigen::Vector2d::Zero()}, b{Eigen::Vector2d::Zero()};
  Eigen::Vector2d normal{Eigen::Vector2d::UnitX()};  // horizontal, towards the sensor
  double length{0.0};
};

/// The S-Graph's wall-grade planes: vertical, finite, at least surface_min_length long and
/// surface_min_height tall (a low cupboard, a plane of a few points is not a wall).
std::vector<WallSegment> WallSegments(const sgraph::SGraph& graph, const MatcherConfig& config);

/// Wall planes as evidence for a hypothesis beyond its room pairs: the robot maps walls it does
/// not enclose in a room (seen through a doorway, a corridor's far end, a façade). Under the
/// true motion they lie on the BIM's wall-surfaces; under a wrong one fewer do. A plane's
/// evidence is min(1, length / surface_full_length) x the share of its extent that lies on
/// A-surfaces of the storey facing the same way (normal within angle_tolerance_deg, offset
/// within offset_tolerance); a plane along several collinear A-surfaces (a corridor wall split
/// at doors) counts them together. Only positive: clutter, walls built off the plan or not in it
/// explain nothing but contradict nothing either. A-surfaces are hashed into 1 m cells per
/// storey.
class SurfaceEvidence {
 public:
  SurfaceEvidence() = default;
  SurfaceEvidence(const agraph::AGraph& graph, const MatcherConfig& config);

  /// The share of `plane`'s extent (0..1) lying on A-surfaces of `storey` under `pose`.
  double Share(const WallSegment& plane, const Pose2& pose, int storey) const;
  /// Σ over `planes` of min(1, length / surface_full_length) x Share.
  double Explained(const std::vector<WallSegment>& planes, const Pose2& pose, int storey) const;
  /// The most Explained can give `planes` under any motion: Σ min(1, length / full length).
  double Bound(const std::vector<WallSegment>& planes) const;
  /// Σ over `planes` of min(1, length / surface_full_length) x the share of the plane lying
  /// beyond the outline of `storey` (the convex hull of its wall-surfaces) by more than
  /// outside_margin under `pose`: walls that, under it, stand outside the building. Walls built
  /// off the plan inside it (moved, extra partitions) never do; under a half-turned twin a
  /// corridor seen to its far end can. 0 for a storey of fewer than three surface ends.
  double Outside(const std::vector<WallSegment>& planes, const Pose2& pose, int storey) const;

  /// An A-surface a plane lies along (facing the same way, within offset_tolerance).
  struct Along {
    int id{0};  // A-Graph wall-surface id
    Eigen::Vector2d normal{Eigen::Vector2d::UnitX()};
    double d{0.0};  // normal . p on the surface
    Eigen::Vector2d middle{Eigen::Vector2d::Zero()};
    double from{0.0}, to{0.0};  // the stretch of the plane along it (m from the plane's a)
  };
  /// The A-surfaces of `storey` that `plane` lies along under `pose` (those Share counts).
  std::vector<Along> AlongSurfaces(const WallSegment& plane, const Pose2& pose, int storey) const;
  /// The A-surfaces of `storey` that `plane` lies behind under `pose`, facing the same way,
  /// further than offset_tolerance and within the thickness of the surface's wall: in the wall's
  /// depth, where only an opening (a window's pane or reveal, a door leaf) can be seen. Share
  /// counts them as explained; they are no face to pair the plane with.
  std::vector<Along> InWallDepth(const WallSegment& plane, const Pose2& pose, int storey) const;

 private:
  struct Surface {
    int id{0};
    Eigen::Vector2d a, b;
    Eigen::Vector2d normal;  // out of the wall's material
    double d;                // normal . p on the surface
    double depth{0.0};       // its wall's thickness behind it (0: unknown)
  };
  struct Storey {
    std::vector<Surface> surfaces;
    std::unordered_map<long long, std::vector<int>> cells;  // 1 m cell -> surface indices
    // The outline's edges (counter-clockwise convex hull): a point, each edge's outward unit
    // normal and offset.
    std::vector<std::pair<Eigen::Vector2d, double>> outline;
  };

  /// AlongSurfaces (in_depth false) or InWallDepth (true).
  std::vector<Along> Stretches(const WallSegment& plane, const Pose2& pose, int storey,
                               bool in_depth) const;

  double cos_angle_{1.0};
  double offset_tolerance_{0.3};
  double full_length_{2.0};
  double outside_margin_{1.0};
  std::unordered_map<int, Storey> storeys_;
};

}  // namespace matching
}  // namespace is_graphs
