// The Eigen decompositions of dynamic-size (real and complex) and of the spatial model's bounded
// double matrices, instantiated once in the library (src/core/eigen_instances.cpp) instead of in
// every translation unit that solves with one: a file that includes this header compiles calls
// to them, not their bodies (a JacobiSVD with its QR preconditioners is about 10 s of compile CPU
// per file at -O3). Not part of the API.
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

// Member templates: instantiating a class does not instantiate them, and a decomposition built
// from a matrix calls compute<InputType>, which holds the whole algorithm of these four
// (tridiagonalisation and QR iteration, Cholesky, LDL^T, Hessenberg and real Schur).
NOCDYN_EIGEN_INSTANCE Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>&
Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>::compute<Eigen::MatrixXd>(const Eigen::EigenBase<Eigen::MatrixXd>&, int);
NOCDYN_EIGEN_INSTANCE Eigen::LLT<Eigen::MatrixXd>& Eigen::LLT<Eigen::MatrixXd>::compute<Eigen::MatrixXd>(
    const Eigen::EigenBase<Eigen::MatrixXd>&);
NOCDYN_EIGEN_INSTANCE Eigen::LDLT<Eigen::MatrixXd>& Eigen::LDLT<Eigen::MatrixXd>::compute<Eigen::MatrixXd>(
    const Eigen::EigenBase<Eigen::MatrixXd>&);
NOCDYN_EIGEN_INSTANCE Eigen::EigenSolver<Eigen::MatrixXd>&
Eigen::EigenSolver<Eigen::MatrixXd>::compute<Eigen::MatrixXd>(const Eigen::EigenBase<Eigen::MatrixXd>&, bool);

// The spatial model's bounded matrices (nocdyn/spatial.hpp): the Gram matrices of the task space
// (TaskMatrix, at most 6 x 6) and a limb's Jacobian (LimbJacobian, 6 x at most kMaxFreedoms = 6).
// Should those bounds change, these declarations no longer match and each file compiles its own.
NOCDYN_EIGEN_INSTANCE class Eigen::SelfAdjointEigenSolver<
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>>;
NOCDYN_EIGEN_INSTANCE Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>>&
Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>>::compute<
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>>(
    const Eigen::EigenBase<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>>&, int);
NOCDYN_EIGEN_INSTANCE class Eigen::PartialPivLU<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>>;
NOCDYN_EIGEN_INSTANCE class Eigen::HouseholderQR<Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>>;

#undef NOCDYN_EIGEN_INSTANCE
