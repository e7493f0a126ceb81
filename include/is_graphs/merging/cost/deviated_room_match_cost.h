#pragma once

#include <ceres/dynamic_autodiff_cost_function.h>

#include <Eigen/Core>
#include <utility>
#include <vector>

namespace is_graphs {
namespace merging {

/// RoomMatchCost (or, given the corridor's across direction, CorridorMatchCost) against an A-room
/// centre moved with its walls' as-built deviations (issue 21). A room whose wall was built 25 cm
/// off has its S-room centre 12.5 cm from the plan's; matched to the planned centre it pulls the
/// pose by that much. With RoomCentreShifts' g_k, the centre matched is α + Σ_k g_k δ_k:
///
///   e = R_2(yaw) ρ + (x, y) − (α_x, α_y) − Σ_k g_k δ_k
///   residual (2) = e / σ             (a room)
///   residual (1) = (R_2(yaw) u)·e / σ   (a corridor, u the unit direction across it in M)
///
/// Parameter blocks:
///   ξ    B_x_M (3): x, y, yaw
///   ρ    S-room centre (2)
///   α    A-room centre (3); its height is not used
///   d_k  deviation (2) of the k-th wall bounding the room: δ [m], θ [rad] (unused); one per g_k
class DeviatedRoomMatchCost {
 public:
  /// `across` zero for a room.
  DeviatedRoomMatchCost(std::vector<Eigen::Vector2d> per_offset, const Eigen::Vector2d& across,
                        double sigma)
      : per_offset_(std::move(per_offset)), across_(across), inv_sigma_(1.0 / sigma) {}

  template <typename T>
  bool operator()(T const* const* blocks, T* residual) const {
    using std::cos;
    using std::sin;
    const T* xi = blocks[0];
    const T* rho = blocks[1];
    const T* alpha = blocks[2];
    const T c = cos(xi[2]), s = sin(xi[2]);
    T ex = c * rho[0] - s * rho[1] + xi[0] - alpha[0];
    T ey = s * rho[0] + c * rho[1] + xi[1] - alpha[1];
    for (size_t k = 0; k < per_offset_.size(); ++k) {
      const T delta = blocks[3 + k][0];
      ex -= T(per_offset_[k].x()) * delta;
      ey -= T(per_offset_[k].y()) * delta;
    }
    if (Corridor()) {
      const T ux = c * T(across_.x()) - s * T(across_.y());
      const T uy = s * T(across_.x()) + c * T(across_.y());
      residual[0] = (ux * ex + uy * ey) * T(inv_sigma_);
    } else {
      residual[0] = ex * T(inv_sigma_);
      residual[1] = ey * T(inv_sigma_);
    }
    return true;
  }

  /// σ must be positive; `across` zero (a room) or unit (a corridor).
  static ceres::CostFunction* Create(std::vector<Eigen::Vector2d> per_offset,
                                     const Eigen::Vector2d& across, double sigma) {
    const size_t walls = per_offset.size();
    auto* functor = new DeviatedRoomMatchCost(std::move(per_offset), across, sigma);
    const int residuals = functor->Corridor() ? 1 : 2;
    auto* cost = new ceres::DynamicAutoDiffCostFunction<DeviatedRoomMatchCost, 4>(functor);
    cost->AddParameterBlock(3);
    cost->AddParameterBlock(2);
    cost->AddParameterBlock(3);
    for (size_t k = 0; k < walls; ++k) cost->AddParameterBlock(2);
    cost->SetNumResiduals(residuals);
    return cost;
  }

 private:
  bool Corridor() const { return across_.squaredNorm() > 0.25; }

  std::vector<Eigen::Vector2d> per_offset_;
  Eigen::Vector2d across_;
  double inv_sigma_;
};

}  // namespace merging
}  // namespace is_graphs
