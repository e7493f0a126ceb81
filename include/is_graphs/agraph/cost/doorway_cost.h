#pragma once

#include <ceres/autodiff_cost_function.h>

#include <Eigen/Core>

namespace is_graphs {
namespace agraph {

/// Relates a doorway to one room it connects: the offset room centre − doorway stays at its
/// BIM value m (measured in the BIM, in the BIM frame):
///
///   residual (3) = Σ^{-1/2} ((ρ − δ) − m)
///
/// Parameter blocks:
///   δ  doorway position (3)
///   ρ  room centre (3)
///
/// One term per connected room: an interior doorway gets two (the 6-residual doorway factor of
/// iS-Graphs, split in two blocks with a block-diagonal weight), a door to outdoors gets one.
class DoorwayRoomCost {
 public:
  DoorwayRoomCost(const Eigen::Vector3d& measured_offset, const Eigen::Matrix3d& sqrt_information)
      : measured_offset_(measured_offset), sqrt_information_(sqrt_information) {}

  template <typename T>
  bool operator()(const T* const doorway, const T* const room, T* residual) const {
    using Vector3T = Eigen::Matrix<T, 3, 1>;
    const Eigen::Map<const Vector3T> delta(doorway);
    const Eigen::Map<const Vector3T> rho(room);
    Eigen::Map<Vector3T> r(residual);
    r = sqrt_information_.template cast<T>() *
        ((rho - delta) - measured_offset_.template cast<T>());
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector3d& measured_offset,
                                     const Eigen::Matrix3d& sqrt_information) {
    return new ceres::AutoDiffCostFunction<DoorwayRoomCost, 3, 3, 3>(
        new DoorwayRoomCost(measured_offset, sqrt_information));
  }

 private:
  Eigen::Vector3d measured_offset_;
  Eigen::Matrix3d sqrt_information_;
};

}  // namespace agraph
}  // namespace is_graphs
