#pragma once

#include <Eigen/Geometry>
#include <string>

#include "is_graphs/geometry/triangle_mesh.h"
#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace sgraph {

/// The IFC class ("IfcWallStandardCase", "IfcWindow", ...) of the building mesh that an S-Graph
/// plane lies on, after `bim_T_map`: of the mesh triangles parallel to it (10°), within
/// `tolerance` of it and inside its extent (horizontal and vertical, 0.1 m margin), the class
/// holding the largest area; "" when none. Tells a mapped wall from a window or door set back in
/// it (FZK-Haus' windows sit 12 cm behind the inner wall faces), which the A-Graph's
/// wall-surfaces cannot.
std::string PlaneSupportClass(const Plane& plane, const Eigen::Isometry3d& bim_T_map,
                              const geometry::TriangleMesh& mesh, double tolerance);

}  // namespace sgraph
}  // namespace is_graphs
