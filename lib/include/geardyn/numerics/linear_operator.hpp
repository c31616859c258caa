/// @file
/// @brief The linear-operator concept the eigen and monodromy solvers are written against
/// (architecture §3.4, after Spectra's operators): `LinearOperator` (y = A x) and
/// `ShiftSolveOperator` (the shift-invert operator y = (K − σM)⁻¹ M x of the generalized symmetric
/// pencil (K, M)), with dense and sparse implementations.
///
/// **Concept.** A `LinearOperator` has `rows()` and `Apply(x, y)` writing y = A x into a
/// caller-sized buffer; a `ShiftSolveOperator` is a `LinearOperator` whose Apply is
/// y = (K − σM)⁻¹ M x and that also offers `Solve(b, y)`: y = (K − σM)⁻¹ b (ARPACK's mode 3 hands
/// over M x when it already has it), `sigma()` and the `factorization()` report. Solvers take the
/// operator as a template parameter, so dense, sparse and (later) matrix-free storage differ only
/// in the operator, and no virtual call is made per application.
///
/// **Factorization of K − σM.** K − σM is symmetric but, for a shift inside the spectrum,
/// indefinite. `ShiftFactorization::kAuto` first factorizes it with LDLᵀ (dense: Eigen::LDLT, which
/// pivots on the diagonal; sparse: Eigen::SimplicialLDLT with AMD ordering, no pivoting) and keeps
/// that factorization only when every pivot of D is positive and finite, i.e. when K − σM is
/// positive definite (Sylvester's law of inertia), where LDLᵀ without pivoting is backward stable.
/// Otherwise (indefinite, or a zero pivot) it refactorizes with an LU with partial pivoting
/// (dense: Eigen::PartialPivLU; sparse: Eigen::SparseLU with COLAMD ordering), which is stable for
/// indefinite matrices. With K positive semidefinite and M positive definite, every σ < 0 gives a
/// positive definite K − σM, so the default shifts of the eigen solvers take the LDLᵀ path.
///
/// **Singular shift.** After factorizing, the operator estimates cond₁(K − σM) from ‖K − σM‖₁
/// and two steps of inverse iteration from a fixed pseudo-random vector (a lower bound of the true
/// condition number, within a small factor of it when K − σM is nearly singular). If the solve
/// fails, produces non-finite values, or the estimate exceeds `kSingularShiftCondition`
/// (= 1/(100 ε) ≈ 4.5e13), σ is an eigenvalue of the pencil to working precision: `ok()` is false
/// and `factorization().message` says so. Nothing is thrown for this numerical outcome; solvers
/// turn it into a Summary status (architecture §3.7). Apply/Solve must not be called then.
///
/// **Lifetime and threads.** The matrix operators and the shift-solve operators keep a pointer to
/// the matrices they apply (A, resp. M), as Spectra's operators do: those must outlive the
/// operator. The shift-solve operators own their factorization. Apply/Solve are const but the
/// shift-solve operators use an internal scratch vector: use one operator per thread.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <concepts>
#include <limits>
#include <string>

#include "geardyn/common/eigen_types.hpp"

namespace geardyn {

/// @brief y = A x for a square operator A of size rows() × rows().
template <class Op>
concept LinearOperator = requires(const Op& op, Eigen::Map<const VectorX> x,
                                  Eigen::Map<VectorX> y) {
  { op.rows() } -> std::convertible_to<Eigen::Index>;
  op.Apply(x, y);
};

/// @brief Which factorization of K − σM a shift-solve operator uses.
enum class ShiftFactorization {
  kAuto,  ///< LDLᵀ when K − σM is positive definite, else LU (see the file comment)
  kLdlt,  ///< always LDLᵀ (dense: diagonal pivoting; sparse: none); may be unstable if indefinite
  kLu,    ///< always LU with partial pivoting
};

/// @brief Text name of a factorization choice ("auto", "ldlt", "lu").
const char* ShiftFactorizationName(ShiftFactorization factorization);

/// Condition-number estimate of K − σM above which σ is treated as an eigenvalue: 1/(100 ε).
inline constexpr double kSingularShiftCondition =
    1.0 / (100.0 * std::numeric_limits<double>::epsilon());

/// @brief What the shift-solve operator's constructor did, and whether it can be applied.
struct ShiftFactorizationReport {
  bool ok = false;                                      ///< factorized and not numerically singular
  ShiftFactorization used = ShiftFactorization::kAuto;  ///< kLdlt or kLu after construction
  bool positive_definite = false;  ///< LDLᵀ found only positive pivots (K − σM is SPD)
  int num_factorizations = 0;      ///< 1, or 2 when kAuto fell back from LDLᵀ to LU
  double condition_estimate = 0;   ///< lower-bound estimate of cond₁(K − σM) [-]
  std::string message;             ///< why ok is false (empty otherwise)
};

/// @brief A `LinearOperator` whose Apply is y = (K − σM)⁻¹ M x, with Solve(b, y): y = (K − σM)⁻¹ b.
template <class Op>
concept ShiftSolveOperator = LinearOperator<Op> &&
    requires(const Op& op, Eigen::Map<const VectorX> b, Eigen::Map<VectorX> y) {
  op.Solve(b, y);
  { op.sigma() } -> std::convertible_to<double>;
  { op.ok() } -> std::convertible_to<bool>;
  { op.factorization() } -> std::convertible_to<const ShiftFactorizationReport&>;
};

/// @brief y = A x for a dense square matrix A (not owned: A must outlive the operator).
class DenseMatrixOperator {
 public:
  /// @param[in] A (n × n) the matrix, in any consistent unit.
  /// @throws InvalidInput naming `A` if it is not square.
  explicit DenseMatrixOperator(const MatrixX& A);

  /// n [-].
  Eigen::Index rows() const { return A_->rows(); }
  /// @brief y = A x.
  /// @param[in] x (n) input; must not overlap y.
  /// @param[out] y (n) output, sized by the caller.
  void Apply(const Eigen::Ref<const VectorX>& x, Eigen::Ref<VectorX> y) const;

 private:
  const MatrixX* A_;
};

/// @brief y = A x for a sparse square matrix A (not owned: A must outlive the operator).
class SparseMatrixOperator {
 public:
  /// @param[in] A (n × n) the matrix, in any consistent unit.
  /// @throws InvalidInput naming `A` if it is not square.
  explicit SparseMatrixOperator(const SparseMatrix& A);

  /// n [-].
  Eigen::Index rows() const { return A_->rows(); }
  /// @brief y = A x.
  /// @param[in] x (n) input; must not overlap y.
  /// @param[out] y (n) output, sized by the caller.
  void Apply(const Eigen::Ref<const VectorX>& x, Eigen::Ref<VectorX> y) const;

 private:
  const SparseMatrix* A_;
};

namespace internal {

/// @brief What the dense and sparse shift-invert operators share: the accessors, Solve and Apply
/// over an LDLᵀ (`Ldlt`) or LU (`Lu`) factorization of K − σM, chosen by the derived constructor.
/// M is not owned: it must outlive the operator.
template <class Matrix, class Ldlt, class Lu>
class ShiftSolveOperatorBase {
 public:
  /// n [-].
  Eigen::Index rows() const { return M_->rows(); }
  /// σ [units of K/M].
  double sigma() const { return sigma_; }
  /// True when K − σM was factorized and is not numerically singular.
  bool ok() const { return report_.ok; }
  /// What the constructor did.
  const ShiftFactorizationReport& factorization() const { return report_; }

  /// @brief y = (K − σM)⁻¹ M x.
  /// @pre ok(); x and y do not overlap.
  /// @param[in] x (n) input.
  /// @param[out] y (n) output, sized by the caller.
  /// @throws InternalError if !ok().
  void Apply(const Eigen::Ref<const VectorX>& x, Eigen::Ref<VectorX> y) const;
  /// @brief y = (K − σM)⁻¹ b.
  /// @pre ok(). @param[in] b (n) right-hand side. @param[out] y (n) solution, caller-sized.
  /// @throws InternalError if !ok().
  void Solve(const Eigen::Ref<const VectorX>& b, Eigen::Ref<VectorX> y) const;

 protected:
  ShiftSolveOperatorBase(const Matrix& M, double sigma)
      : M_(&M), sigma_(sigma), scratch_(M.rows()) {}

  /// After an LDLᵀ attempt `ldlt` (named `name` in messages): counts it, records whether its
  /// pivots are all positive and sets report_.used to kLdlt when forced or positive definite.
  /// False when a forced LDLᵀ failed (report_ then says why).
  bool RecordLdlt(const Ldlt& ldlt, ShiftFactorization factorization, const char* name);
  /// Estimates the condition from ‖K − σM‖₁ = norm1 with the chosen factorization and sets ok.
  void FinishFactorization(double norm1);

  const Matrix* M_;
  double sigma_;
  ShiftFactorizationReport report_;
  Ldlt ldlt_;
  Lu lu_;
  mutable VectorX scratch_;
};

extern template class ShiftSolveOperatorBase<MatrixX, Eigen::LDLT<MatrixX>,
                                             Eigen::PartialPivLU<MatrixX>>;
extern template class ShiftSolveOperatorBase<SparseMatrix, Eigen::SimplicialLDLT<SparseMatrix>,
                                             Eigen::SparseLU<SparseMatrix>>;

}  // namespace internal

/// @brief Dense shift-invert operator y = (K − σM)⁻¹ M x (M not owned: it must outlive this).
///
/// rows(), sigma(), ok(), factorization(), Apply(x, y) = (K − σM)⁻¹ M x and Solve(b, y) =
/// (K − σM)⁻¹ b as documented on internal::ShiftSolveOperatorBase.
class DenseShiftSolveOperator
    : public internal::ShiftSolveOperatorBase<MatrixX, Eigen::LDLT<MatrixX>,
                                              Eigen::PartialPivLU<MatrixX>> {
 public:
  /// @brief Factorizes K − σM (see the file comment for the choice and the singularity test).
  /// @param[in] K (n × n) symmetric stiffness [N/m, N·m/rad].
  /// @param[in] M (n × n) symmetric mass [kg, kg·m²], same size as K.
  /// @param[in] sigma σ, finite [units of K/M, e.g. rad²/s²].
  /// @param[in] factorization kAuto (default), or a forced kLdlt / kLu.
  /// @throws InvalidInput naming `K`, `M` or `sigma` for non-square or mismatched sizes, or a
  /// non-finite σ. A singular K − σM is not an exception: see ok().
  DenseShiftSolveOperator(const MatrixX& K, const MatrixX& M, double sigma,
                          ShiftFactorization factorization = ShiftFactorization::kAuto);
};

/// @brief Sparse shift-invert operator y = (K − σM)⁻¹ M x (M not owned: it must outlive this).
///
/// rows(), sigma(), ok(), factorization(), Apply and Solve as on DenseShiftSolveOperator.
/// Not copyable (it owns Eigen's sparse factorizations).
class SparseShiftSolveOperator
    : public internal::ShiftSolveOperatorBase<SparseMatrix, Eigen::SimplicialLDLT<SparseMatrix>,
                                              Eigen::SparseLU<SparseMatrix>> {
 public:
  /// @brief Factorizes K − σM (see the file comment for the choice and the singularity test).
  /// @param[in] K (n × n) symmetric stiffness [N/m, N·m/rad]; both triangles stored.
  /// @param[in] M (n × n) symmetric mass [kg, kg·m²], same size as K; both triangles stored.
  /// @param[in] sigma σ, finite [units of K/M, e.g. rad²/s²].
  /// @param[in] factorization kAuto (default), or a forced kLdlt / kLu.
  /// @throws InvalidInput naming `K`, `M` or `sigma` for non-square or mismatched sizes, or a
  /// non-finite σ. A singular K − σM is not an exception: see ok().
  SparseShiftSolveOperator(const SparseMatrix& K, const SparseMatrix& M, double sigma,
                           ShiftFactorization factorization = ShiftFactorization::kAuto);
  SparseShiftSolveOperator(const SparseShiftSolveOperator&) = delete;
  SparseShiftSolveOperator& operator=(const SparseShiftSolveOperator&) = delete;
};

static_assert(LinearOperator<DenseMatrixOperator>);
static_assert(LinearOperator<SparseMatrixOperator>);
static_assert(ShiftSolveOperator<DenseShiftSolveOperator>);
static_assert(ShiftSolveOperator<SparseShiftSolveOperator>);

}  // namespace geardyn
