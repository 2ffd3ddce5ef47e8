#pragma once
// The thesis building's sizes (6 DOFs, 12 states, inputs a_g and F_d), for
// the fixed-size checks of the structure tests.
#include <Eigen/Core>

namespace mrd::structure::thesis_sizes {
constexpr int kDofs = 6;
constexpr int kStates = 2 * kDofs;
using Matrix6 = Eigen::Matrix<double, kDofs, kDofs>;
using Vector6 = Eigen::Matrix<double, kDofs, 1>;
using StateMatrix = Eigen::Matrix<double, kStates, kStates>;
using State = Eigen::Matrix<double, kStates, 1>;
using Input = Eigen::Matrix<double, 2, 1>;
}  // namespace mrd::structure::thesis_sizes
