// The Eigen decompositions of dynamic-size (real and complex) double matrices, instantiated once in the library
// (src/core/eigen_instances.cpp) instead of in every translation unit that solves with one: a
// file that includes this header compiles calls to them, not their bodies (a JacobiSVD with its
// QR preconditioners is about 10 s of compile CPU per file at -O3). Not part of the API.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>

// NOCDYN_EIGEN_INSTANCES is defined only in the file that instantiates them
#ifndef NOCDYN_EIGEN_INSTANCES
#define NOCDYN_EIGEN_INSTANCE extern template
#else
#define NOCDYN_EIGEN_INSTANCE template
#endif

NOCDYN_EIGEN_INSTANCE class Eigen::JacobiSVD<Eigen::MatrixXd>;
NOCDYN_EIGEN_INSTANCE class Eigen::ColPivHouseholderQR<Eigen::MatrixXd>;
NOCDYN_EIGEN_INSTANCE class Eigen::HouseholderQR<Eigen::MatrixXd>;
NOCDYN_EIGEN_INSTANCE class Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>;
NOCDYN_EIGEN_INSTANCE class Eigen::LLT<Eigen::MatrixXd>;
NOCDYN_EIGEN_INSTANCE class Eigen::LDLT<Eigen::MatrixXd>;
NOCDYN_EIGEN_INSTANCE class Eigen::PartialPivLU<Eigen::MatrixXd>;
NOCDYN_EIGEN_INSTANCE class Eigen::FullPivLU<Eigen::MatrixXd>;
NOCDYN_EIGEN_INSTANCE class Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>;
NOCDYN_EIGEN_INSTANCE class Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>;
NOCDYN_EIGEN_INSTANCE class Eigen::EigenSolver<Eigen::MatrixXd>;
// frequency responses: (s I - A)^-1 B
NOCDYN_EIGEN_INSTANCE class Eigen::PartialPivLU<Eigen::MatrixXcd>;
NOCDYN_EIGEN_INSTANCE class Eigen::FullPivLU<Eigen::MatrixXcd>;

#undef NOCDYN_EIGEN_INSTANCE
