/// @file
/// @brief Fourier expansion of the periodic linear system in the system phase θ (spec 02
/// "Harmonic balance" and "Hill's method"): K(θ) = Σ_{m=−N..N} K_m e^{imθ/P}, likewise C(θ) and
/// f(θ), with K_{−m} = conj(K_m) (real K). θ and P as in system_steps.hpp (one mesh frequency;
/// period 2π·P; harmonic m has m/P times the mesh frequency).
///
/// **Per mesh first.** The mesh terms are Gᵀ X2_m G with the 2×2 harmonics X2_m of the core's
/// K2(θ_k), C2(θ_k) and load pair K2 ε (θ_k = θ + φ_k, so X2_m of the system carries the factor
/// e^{imφ_k/P}). MeshHarmonics keeps these 2×2 blocks (O(N) memory per mesh, what matrix-free
/// large-system solvers need); AssembleSystemHarmonics scatters them into dense n×n matrices for
/// small systems.
///
/// **Exactness.** When every coefficient a mesh's values depend on (stiffness channels and, for
/// the load, ε) is constant or piecewise constant, K2, C2 = (c_m/K) K2 and K2 ε are piecewise
/// constant on the union of the breakpoints, and their harmonics are the exact closed form of
/// ToFourier (sinc sums). Otherwise they are sampled on S points per mesh period and
/// transformed (FFTW): exact for Fourier-series coefficients as long as S exceeds twice the
/// highest harmonic of the product (S is chosen so: S ≥ 2(N_k + 2 N_c) + 2 with N_c the
/// coefficient's own terms and N_k the requested mesh harmonics, at least
/// kMinSamplesPerMeshPeriod); tables are represented by their trigonometric interpolant.
/// A linear core whose ε repeats over a longer period than its stiffness (tooth errors, the
/// hunting period) is not sampled over that period: K2 and C2 come from one stiffness period and
/// the load K2 ε is the convolution of their harmonics with ε's own (FFT synthesis), exact for
/// that ε.
#pragma once

#include <complex>
#include <cstdint>
#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn {

/// Fewest samples per mesh period used for smooth coefficients.
inline constexpr int kMinSamplesPerMeshPeriod = 256;

using Matrix2c = Eigen::Matrix2cd;
using Vector2c = Eigen::Vector2cd;

/// @brief The 2×2 harmonics of one mesh in the system phase, m = 0 … N (index m).
struct MeshHarmonics {
  std::vector<Matrix2c> stiffness;  ///< K2_m [N/m, N, N·m]
  std::vector<Matrix2c> damping;    ///< C2_m [N·s/m, N·s, N·m·s]
  std::vector<Vector2c> load;       ///< (K2 ε)_m [N, N·m]
};

/// @brief Dense system harmonics, m = 0 … N (index m); negative m by conjugation.
struct SystemHarmonics {
  std::int64_t period_meshes = 1;   ///< P: harmonic m has frequency m/P × mesh frequency
  std::vector<MatrixXc> stiffness;  ///< (n×n) K_m, K_0 = K0 + mean of the mesh terms
  std::vector<MatrixXc> damping;    ///< (n×n) C_m, C_0 includes C0
  std::vector<VectorXc> load;       ///< (n) f_m, f_0 includes f0, f_{lP} the loads' F_l/2
  /// N.
  int num_harmonics() const { return static_cast<int>(stiffness.size()) - 1; }
};

/// @brief The 2×2 harmonics m = 0 … num_harmonics of every mesh (mesh order) in system phase.
/// @throws InvalidInput if num_harmonics < 0 or a mesh's phase ratio is not 1.
std::vector<MeshHarmonics> ExpandMeshHarmonics(const SystemModel& model, int num_harmonics);

/// @brief The harmonics of one mesh that a forced response over a long hunting period needs: the
/// operator at the harmonics jq of the operator frequency, the load and ε at chosen harmonics.
struct SparseMeshHarmonics {
  std::vector<Matrix2c> stiffness;           ///< K2 at system harmonic j·q, j = 0 … J
  std::vector<Matrix2c> damping;             ///< C2 at system harmonic j·q, j = 0 … J
  std::vector<Vector2c> load;                ///< (K2 ε) at harmonics[i] [N, N·m]
  std::vector<Vector2c> transmission_error;  ///< ε at harmonics[i] [m, rad]
};

/// @brief The same numbers as ExpandMeshHarmonics (system phase, harmonic m of 1/P), but only at
/// the operator harmonics jq (q = P/operator_period, j = 0 … J) and at the given load harmonics:
/// memory O(J + harmonics), never O(P). The coefficient part of each core (its stiffness and ε
/// coefficient, period P_b) is expanded at its own period up to the harmonic the request
/// reaches, the sidebands (TransmissionErrorSidebands) add their lines exactly.
/// @param[in] operator_period P_K: a multiple of every core's stiffness period dividing P.
/// @param[in] J ≥ 0 operator harmonics. @param[in] harmonics load harmonics m ≥ 0 (of 1/P).
/// @throws InvalidInput on a negative m or J, a phase ratio ≠ 1, a coefficient part whose
///   expansion would need more than 2^24 harmonics (a long-period ε coefficient: pitch errors).
std::vector<SparseMeshHarmonics> ExpandMeshHarmonicsSparse(
    const SystemModel& model, std::int64_t operator_period, int J,
    const std::vector<std::int64_t>& harmonics);

/// @brief One mesh's harmonics n = 0 … num_harmonics in its OWN phase, for analyses where the
/// meshes run at different frequencies (the quasi-periodic harmonic balance): with u = θ_k − φ_k
/// (θ_k = SystemMesh::MeshPhase) and P_k the core's period (mesh cycles), K2(θ_k) =
/// Σ_n stiffness[n] e^{inu/P_k} (n < 0 by conjugation), likewise damping, the load K2 ε
/// (load[n]) and ε (transmission_error[n]); the factor e^{inφ_k/P_k} of the offset is included.
/// The same numbers as ExpandMeshHarmonicsSparse for a model whose only mesh is this one.
/// @throws InvalidInput on num_harmonics < 0 or an expansion of more than 2^24 harmonics.
SparseMeshHarmonics ExpandOwnPhaseMeshHarmonics(const SystemMesh& mesh, int num_harmonics);

/// @brief K_m, C_m, f_m as dense n×n / n (O(N n²) memory: small systems only).
SystemHarmonics AssembleSystemHarmonics(const SystemModel& model,
                                        const std::vector<MeshHarmonics>& meshes);

/// @brief ExpandMeshHarmonics then AssembleSystemHarmonics.
SystemHarmonics ExpandSystemHarmonics(const SystemModel& model, int num_harmonics);

}  // namespace geardyn
