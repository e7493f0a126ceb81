#pragma once
// Test helper: a cost functor's autodiff Jacobians against central numeric differentiation.

#include <ceres/cost_function.h>
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace is_graphs {
namespace testing {

/// Evaluates both cost functions at `parameters` and expects equal residuals and Jacobians.
inline void ExpectSameEvaluation(const ceres::CostFunction& autodiff,
                                 const ceres::CostFunction& numeric,
                                 const std::vector<const double*>& parameters,
                                 double tolerance = 1e-7) {
  const int num_residuals = autodiff.num_residuals();
  const std::vector<int32_t>& sizes = autodiff.parameter_block_sizes();
  ASSERT_EQ(sizes.size(), parameters.size());
  ASSERT_EQ(numeric.num_residuals(), num_residuals);
  std::vector<Eigen::VectorXd> residuals(2, Eigen::VectorXd(num_residuals));
  std::vector<std::vector<Eigen::MatrixXd>> jacobians(2);  // row-major data, via transposes
  const ceres::CostFunction* functions[2] = {&autodiff, &numeric};
  for (int f = 0; f < 2; ++f) {
    std::vector<std::vector<double>> storage;
    std::vector<double*> pointers;
    for (int32_t size : sizes) storage.emplace_back(num_residuals * size);
    for (auto& s : storage) pointers.push_back(s.data());
    ASSERT_TRUE(functions[f]->Evaluate(parameters.data(), residuals[f].data(), pointers.data()));
    for (size_t b = 0; b < sizes.size(); ++b) {
      // ceres stores each Jacobian block row-major: num_residuals x size.
      jacobians[f].push_back(
          Eigen::Map<Eigen::MatrixXd>(storage[b].data(), sizes[b], num_residuals).transpose());
    }
  }
  EXPECT_LT((residuals[0] - residuals[1]).norm(), tolerance);
  for (size_t b = 0; b < sizes.size(); ++b) {
    EXPECT_LT((jacobians[0][b] - jacobians[1][b]).norm(), tolerance)
        << "parameter block " << b << "\nautodiff:\n"
        << jacobians[0][b] << "\nnumeric:\n"
        << jacobians[1][b];
  }
}

/// The residual of a cost function at `parameters`.
inline Eigen::VectorXd Residual(const ceres::CostFunction& cost,
                                const std::vector<const double*>& parameters) {
  Eigen::VectorXd residual(cost.num_residuals());
  EXPECT_TRUE(cost.Evaluate(parameters.data(), residual.data(), nullptr));
  return residual;
}

}  // namespace testing
}  // namespace is_graphs
