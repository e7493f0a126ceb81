#include "is_graphs/sgraph/floor_node.h"

namespace is_graphs {
namespace sgraph {

Floor MakeFloor(const std::vector<Room>& rooms, double height) {
  Floor floor;
  floor.height = height;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& r : rooms) {
    sum += r.center;
    floor.rooms.push_back(r.id);
  }
  if (!rooms.empty()) floor.center = sum / static_cast<double>(rooms.size());
  floor.center.z() = height;
  return floor;
}

}  // namespace sgraph
}  // namespace is_graphs
