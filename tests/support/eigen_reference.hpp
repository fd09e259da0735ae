// SPDX-License-Identifier: Apache-2.0
// tests/support/eigen_reference.hpp: Eigen's decompositions, in double, as the tests' independent
// references. They are compiled once, in eigen_reference.cpp: instantiated in a test's own file,
// each cost that file 4–7 s of compile time, in every host preset.
#pragma once

#include <Eigen/Core>

namespace uvms_test {

// A = U·diag(σ)·Vᵀ (Eigen::JacobiSVD, full U and V), σ in decreasing order; `rank` as
// JacobiSVD::rank() counts it (its default threshold).
struct Svd {
  Eigen::VectorXd singular_values;
  Eigen::MatrixXd U, V;
  Eigen::Index rank;
};
Svd SvdOf(const Eigen::MatrixXd &A);

// The Moore–Penrose pseudoinverse A⁺, by complete orthogonal decomposition.
Eigen::MatrixXd PseudoInverse(const Eigen::MatrixXd &A);

// The eigenvalues of a symmetric matrix, in increasing order (Eigen::SelfAdjointEigenSolver).
Eigen::VectorXd SymmetricEigenvalues(const Eigen::MatrixXd &A);

}  // namespace uvms_test
