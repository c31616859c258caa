/// @file
/// @brief The Eigen decompositions compiled once, in geardyn::core, instead of in every
/// translation unit that uses them: explicit instantiation declarations (`extern template`).
///
/// A build-speed device, not an API. Eigen's dense eigensolvers and factorizations are templates
/// that every user instantiates and optimizes again: `GeneralizedSelfAdjointEigenSolver<MatrixXd>`
/// alone cost 3.4 s of front end in each of 39 translation units of the test build; declared
/// extern here, the list halved the compile time of tests/lib/system/probes_test.cpp (9.2 → 4.5 s)
/// and took the cold build from 17.4 to 14.9 min (docs/benchmarks.md "Build and CI time"). The
/// precompiled headers of the libraries and the tests include this header
/// (cmake/GeardynBuildSpeed.cmake); `lib/src/numerics/eigen_instantiations.cpp` holds the one
/// explicit instantiation definition of each. Code that does not include it instantiates the
/// same templates implicitly, as usual; both link (the definitions are identical).
///
/// Only non-inline members are affected: inline members are still instantiated where they are
/// used. Member templates (the `compute<InputType>` of most decompositions) are listed with the
/// input type the code base passes, a plain matrix of the decomposition's own type.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>

// The fixed sizes of the B–S mesh interface (6 DOFs per body, 12 per pair).
namespace geardyn_eigen_instantiations {
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Matrix12d = Eigen::Matrix<double, 12, 12>;
}  // namespace geardyn_eigen_instantiations

// X(declaration): one explicit instantiation per entry. GEARDYN_EIGEN_COMPUTE(D, M, ...) is the
// `D& D::compute<M>(const EigenBase<M>&, ...)` member template of decomposition D.
#define GEARDYN_EIGEN_COMPUTE(D, M, ...) \
  D& D::compute<M>(const Eigen::EigenBase<M>& __VA_OPT__(, ) __VA_ARGS__)

#define GEARDYN_EIGEN_INSTANTIATIONS(X)                                                           \
  X(class Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>)                              \
  X(class Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>)                                         \
  X(GEARDYN_EIGEN_COMPUTE(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>, Eigen::MatrixXd, int))  \
  X(class Eigen::SelfAdjointEigenSolver<geardyn_eigen_instantiations::Matrix6d>)                  \
  X(GEARDYN_EIGEN_COMPUTE(Eigen::SelfAdjointEigenSolver<geardyn_eigen_instantiations::Matrix6d>,  \
                          geardyn_eigen_instantiations::Matrix6d, int))                           \
  X(class Eigen::SelfAdjointEigenSolver<geardyn_eigen_instantiations::Matrix12d>)                 \
  X(GEARDYN_EIGEN_COMPUTE(Eigen::SelfAdjointEigenSolver<geardyn_eigen_instantiations::Matrix12d>, \
                          geardyn_eigen_instantiations::Matrix12d, int))                          \
  X(class Eigen::EigenSolver<Eigen::MatrixXd>)                                                    \
  X(GEARDYN_EIGEN_COMPUTE(Eigen::EigenSolver<Eigen::MatrixXd>, Eigen::MatrixXd, bool))            \
  X(class Eigen::EigenSolver<Eigen::Matrix2d>)                                                    \
  X(GEARDYN_EIGEN_COMPUTE(Eigen::EigenSolver<Eigen::Matrix2d>, Eigen::Matrix2d, bool))            \
  X(class Eigen::ComplexEigenSolver<Eigen::MatrixXcd>)                                            \
  X(GEARDYN_EIGEN_COMPUTE(Eigen::ComplexEigenSolver<Eigen::MatrixXcd>, Eigen::MatrixXcd, bool))   \
  X(class Eigen::RealSchur<Eigen::MatrixXd>)                                                      \
  X(GEARDYN_EIGEN_COMPUTE(Eigen::RealSchur<Eigen::MatrixXd>, Eigen::MatrixXd, bool))              \
  X(class Eigen::LLT<Eigen::MatrixXd>)                                                            \
  X(GEARDYN_EIGEN_COMPUTE(Eigen::LLT<Eigen::MatrixXd>, Eigen::MatrixXd))                          \
  X(class Eigen::LDLT<Eigen::MatrixXd>)                                                           \
  X(GEARDYN_EIGEN_COMPUTE(Eigen::LDLT<Eigen::MatrixXd>, Eigen::MatrixXd))                         \
  X(class Eigen::PartialPivLU<Eigen::MatrixXd>)                                                   \
  X(class Eigen::PartialPivLU<Eigen::MatrixXcd>)                                                  \
  X(class Eigen::FullPivLU<Eigen::MatrixXd>)                                                      \
  X(class Eigen::HouseholderQR<Eigen::MatrixXd>)                                                  \
  X(class Eigen::ColPivHouseholderQR<Eigen::MatrixXd>)                                            \
  X(GEARDYN_EIGEN_COMPUTE(Eigen::ColPivHouseholderQR<Eigen::MatrixXd>, Eigen::MatrixXd))          \
  X(class Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>>)

#define GEARDYN_EIGEN_EXTERN_TEMPLATE(...) extern template __VA_ARGS__;
GEARDYN_EIGEN_INSTANTIATIONS(GEARDYN_EIGEN_EXTERN_TEMPLATE)
#undef GEARDYN_EIGEN_EXTERN_TEMPLATE
