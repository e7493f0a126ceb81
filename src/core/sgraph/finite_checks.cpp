#include "is_graphs/sgraph/finite_checks.h"

#include <cmath>

namespace is_graphs {
namespace sgraph {
namespace {

bool Finite(const geometry::Plane& p) { return p.normal.allFinite() && std::isfinite(p.d); }

}  // namespace

std::string FirstNonFinite(const SGraph& graph) {
  if (!std::isfinite(graph.stamp)) return "stamp";
  if (!std::isfinite(graph.odometry_scale)) return "odometry_scale";
  for (const Keyframe& k : graph.keyframes) {
    const std::string name = "keyframe " + std::to_string(k.id) + ": ";
    if (!std::isfinite(k.stamp)) return name + "stamp";
    if (!k.pose.matrix().allFinite()) return name + "pose";
    if (!k.odom_pose.matrix().allFinite()) return name + "odom_pose";
    if (!k.relative_odom.matrix().allFinite()) return name + "relative_odom";
    if (!k.odom_information.allFinite()) return name + "odom_information";
  }
  for (const Plane& p : graph.planes) {
    const std::string name = "plane " + std::to_string(p.id) + ": ";
    if (!Finite(p.plane)) return name + "plane";
    if (!p.covariance.allFinite()) return name + "covariance";
    if (!p.start.allFinite() || !p.end.allFinite()) return name + "extent";
    if (!std::isfinite(p.z_min) || !std::isfinite(p.z_max)) return name + "z_min/z_max";
  }
  for (const PlaneObservation& o : graph.observations) {
    if (!Finite(o.local) || !o.information.allFinite())
      return "observation of plane " + std::to_string(o.plane) + " from keyframe " +
             std::to_string(o.keyframe);
  }
  for (const Room& r : graph.rooms) {
    if (!r.center.allFinite()) return "room " + std::to_string(r.id) + ": center";
    if (!r.information.allFinite()) return "room " + std::to_string(r.id) + ": information";
  }
  for (const Floor& f : graph.floors)
    if (!f.center.allFinite() || !std::isfinite(f.height))
      return "floor " + std::to_string(f.id) + ": center/height";
  for (const Doorway& d : graph.doorways)
    if (!d.position.allFinite() || !std::isfinite(d.width))
      return "doorway " + std::to_string(d.id) + ": position/width";
  return "";
}

}  // namespace sgraph
}  // namespace is_graphs
