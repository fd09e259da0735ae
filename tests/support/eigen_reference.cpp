// SPDX-License-Identifier: Apache-2.0
// tests/support/eigen_reference.cpp: see eigen_reference.hpp.
#include "eigen_reference.hpp"

#include <Eigen/Dense>

namespace uvms_test {

Svd SvdOf(const Eigen::MatrixXd &A) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return Svd{svd.singularValues(), svd.matrixU(), svd.matrixV(), svd.rank()};
}

Eigen::MatrixXd PseudoInverse(const Eigen::MatrixXd &A) {
  return A.completeOrthogonalDecomposition().pseudoInverse();
}

Eigen::VectorXd SymmetricEigenvalues(const Eigen::MatrixXd &A) {
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A, Eigen::EigenvaluesOnly).eigenvalues();
}

}  // namespace uvms_test
