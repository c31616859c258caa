/// @file
/// @brief Eigen aliases used across geardyn (scalar is always double).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <complex>

namespace geardyn {

using VectorX = Eigen::VectorXd;
using MatrixX = Eigen::MatrixXd;
using VectorXc = Eigen::VectorXcd;
using MatrixXc = Eigen::MatrixXcd;
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using Vector2 = Eigen::Vector2d;
using Vector3 = Eigen::Vector3d;
using Vector6 = Eigen::Matrix<double, 6, 1>;
using Vector6c = Eigen::Matrix<std::complex<double>, 6, 1>;
using Vector12 = Eigen::Matrix<double, 12, 1>;
using Matrix2 = Eigen::Matrix2d;
using Matrix3 = Eigen::Matrix3d;
using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Matrix12 = Eigen::Matrix<double, 12, 12>;
using Matrix2x12 = Eigen::Matrix<double, 2, 12>;

}  // namespace geardyn
