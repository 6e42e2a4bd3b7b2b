// Small fixed-size matrix helpers of the spatial model, shared by its kinematics (spatial.cpp)
// and dynamics (spatial_dynamics.cpp). Not part of the API.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>

namespace nocdyn::spatial::small {

/// The inverse of a small fixed-size matrix in place by Eigen's partial-pivoting LU at its fixed
/// size (no allocation; the dynamic-size LU and triangular solves go through their blocked
/// general paths); false when a pivot is zero or not finite.
template <int N>
bool invertInPlace(Eigen::Matrix<double, N, N, Eigen::RowMajor>& a) {
    const Eigen::PartialPivLU<Eigen::Matrix<double, N, N>> lu(a);
    const auto pivots = lu.matrixLU().diagonal().array();
    if (!pivots.isFinite().all() || !(pivots.abs() > 0.0).all()) return false;
    a = lu.inverse();
    return true;
}

/// The Gram matrix G = B^T B of an m x D matrix (m at most kMaxActuators), by rows.
template <int D, typename Matrix>
Eigen::Matrix<double, D, D, Eigen::RowMajor> gramOf(const Matrix& B) {
    Eigen::Matrix<double, D, D, Eigen::RowMajor> G = Eigen::Matrix<double, D, D, Eigen::RowMajor>::Zero();
    for (Eigen::Index r = 0; r < B.rows(); ++r) {
        const Eigen::Matrix<double, 1, D> row = B.row(r);
        G.noalias() += row.transpose() * row;
    }
    return G;
}

}  // namespace nocdyn::spatial::small
