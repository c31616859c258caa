/// @file
/// @brief Nonlinear harmonic balance of an assembled gear system (issue 6, spec 02 "Harmonic
/// balance"): the steady-state DTE with contact loss and back-flank contact of slice meshes,
/// over a mesh-frequency range by pseudo-arclength continuation, on the engine of
/// nonlinear_hb.hpp (AFT with FFTW, Newton with the analytic Jacobian, Floquet stability).
///
/// **Equation.** With the mesh forces F_k(δ_k, θ_k) of the cores (mesh_core.hpp; δ_k = G_k P_k q)
/// \f[ M\ddot q + \bar C \dot q + K_0 q + \sum_k P_k^T G_k^T F_k(G_k P_k q, θ_k) = f_0,
///     \qquad θ = ω_m t, \; θ_k = r_k θ + φ_k, \f]
/// where F_k is, per core form,
/// * SliceMeshCore: the slice force Σ_s k_s(θ) g(δ_η − σ_s δ_ζ − e_s(θ)) [1, −σ_s]ᵀ with the
///   clearance g (contact loss at 0, back flank after the backlash j) — the nonlinear mesh;
/// * LinearMeshCore: K2(θ)(δ − ε(θ)) — linear time-varying (no contact loss).
///
/// **Mapping onto NhbProblem** (q = T z, u = P q):
/// * nonlinear coordinates u: per mesh δ_η, and δ_ζ when the core's force depends on it (B–S
///   linear cores, slice cores whose G has a δ_ζ row on the kept DOFs);
/// * linear part: M, C̄, K̄ = K0 + Σ Gᵀ K̄2 G (the θ-mean all-loaded mesh stiffness) and the
///   law g̃_k(u, θ) = F_k(u, θ) − K̄2_k u (so that D_0 = K̄ is invertible on the flexible
///   coordinates and the law's Jacobian is small in full contact);
/// * C̄ = θ-mean of the assembled damping C(θ) (C0 + mesh damping with every slice loaded): the
///   mesh damper acts also while the teeth separate, as in the SDOF models of Kahraman & Singh
///   (1990) and Blankenship & Kahraman (1995) — the law has no velocity dependence;
/// * blocks: the decoupled DOF groups of the model (SystemModel::blocks()) that no mesh
///   coordinate touches are LTI and loaded by constants only; their static response is solved
///   once (static_response) and they stay out of the HB and of the stability verdict (their
///   undamped modes would have |μ| = 1);
/// * rigid-body modes: the null space V of K̄ (rigid_modes.hpp) on the mesh-coupled blocks is
///   removed exactly by the reduction q = T z, T an orthonormal basis of {q : Vᵀ M q = 0}. It is
///   exact because K̄ V = 0, the mesh deflections do not see V (K̄2 PSD ⇒ the mesh energy is
///   invariant along V) and Rayleigh damping αM + βK̄ does not couple V to T (Vᵀ M T = 0). The part
///   of f0 along V (a torque the supports cannot react) is removed with a warning. The rigid modes'
///   Floquet multipliers (exactly 1) are thereby excluded from the stability verdict;
/// * f0 → Tᵀ f0; f₁ = Tᵀ Σ F_l of the harmonic loads of order 1 (SystemHarmonicLoad; higher
///   orders are refused: NhbProblem forces at Ω only), besides the θ-variation inside g̃;
/// * Ω = ω_m = 2π f_m [rad/s]; period multiple p = P·(requested multiple), P the system's
///   period_meshes() (hunting period); the harmonics H are harmonics of ω_m/p.
///
/// **Outputs** per point: per mesh the DTE (δ_η − ε_η, probes.hpp; ε = 0 for slice cores) mean,
/// RMS, peak-to-peak and harmonic amplitudes, the mesh force F_η (mean, RMS, min, max, the
/// fraction of the period without drive-flank contact, back-flank contact), per element the mean
/// and RMS of its force on its first body (CalcElementForce convention), Floquet stability,
/// branch id, and the error estimate of the engine. Folds and jumps are located on coordinate 0
/// (δ_η of the first mesh).
///
/// Reentrant; never prints. Throws InvalidInput for a NonlinearMeshCore, meshes at different
/// frequencies (CheckSingleMeshFrequency), invalid options, or a model without meshes.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "geardyn/analyses/nonlinear_hb.hpp"
#include "geardyn/common/eigen_types.hpp"
#include "geardyn/common/summary.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn {

/// @brief The gear system as an NhbProblem in the flexible coordinates z (see the @file).
struct SystemNhbProblem {
  NhbProblem problem;  ///< in z: M_z = Tᵀ M T etc., P_z = P T, law = the mesh-force law
  MatrixX reduction;   ///< T (N × N_z): q = T z + static_response, Tᵀ T = I, Vᵀ M T = 0
  /// (N) the static response of the blocks no mesh touches (zero on the mesh-coupled blocks).
  VectorX static_response;
  /// Per nonlinear coordinate: its mesh index and channel (0: δ_η [m], 1: δ_ζ [rad]).
  std::vector<int> coordinate_mesh, coordinate_channel;
  std::vector<int> mesh_eta_coordinate;  ///< per mesh, the index of its δ_η in u
  int period_meshes = 1;                 ///< P
  int rigid_modes = 0;                   ///< dim V
  double unbalanced_load = 0.0;          ///< relative part of f0 along V (removed) [-]
  std::vector<std::string> warnings;
};

/// @brief Builds the SystemNhbProblem of a model (see the @file).
/// @throws InvalidInput on a NonlinearMeshCore, no meshes, or meshes at different frequencies.
SystemNhbProblem MakeSystemNhbProblem(const SystemModel& model);

/// @brief Options of the system sweep.
struct SystemNhbOptions {
  /// Engine options: harmonics H of ω_m/p (0 = traced with H = 8, 16, … until the energy in the
  /// top harmonics is below harmonic_tolerance), samples_per_harmonic, Newton, stability.
  /// With tooth errors repeating every P > 1 mesh cycles the base is ω_m/(p·P) and H must be
  /// ≥ p·P (the mesh harmonic), else InvalidInput; H = 0 is then refused too.
  NhbOptions hb;
  double start_hz = 0.0;  ///< first mesh frequency f_m [Hz] > 0
  double end_hz = 0.0;    ///< last mesh frequency [Hz] > 0, ≠ start_hz
  /// Continuation steps (omega_start/omega_end are set from start_hz/end_hz). The branch search
  /// is on by default here (8 frequencies): 32 Newton solves on the condensed problem.
  NhbContinuationOptions continuation = [] {
    NhbContinuationOptions c;
    c.branch_search = 8;
    return c;
  }();
  bool compute_element_forces = true;  ///< per-element mean/RMS forces (one solve per harmonic)
  bool keep_response = false;          ///< keep Q_k of q in every point (SystemNhbPoint::response)
  /// False (with the field and reason in `why`) on an invalid value.
  bool IsValid(std::string* why) const;
};

/// @brief Steady-state outputs of one mesh at one point.
struct SystemNhbMeshOutput {
  std::string name;
  double mean_dte = 0.0;               ///< [m]
  double rms_dte = 0.0;                ///< RMS of DTE − mean [m]
  double peak_to_peak_dte = 0.0;       ///< [m]
  VectorX dte_amplitudes;              ///< (H+1): |mean|, then 2|Y_k| of harmonic k of ω_m/p [m]
  double mean_force = 0.0;             ///< θ-mean of F_η (elastic part) [N] (> 0: compression)
  double rms_force = 0.0;              ///< RMS of F_η − mean [N]
  double min_force = 0.0;              ///< [N]; < 0 only with back-flank contact
  double max_force = 0.0;              ///< [N]
  double contact_loss_fraction = 0.0;  ///< fraction of the samples without drive-flank contact
  bool back_contact = false;           ///< the back flank carried load at some sample
};

/// @brief Mean and RMS (alternating part) of one element's force on its first body [N, N·m].
struct SystemNhbElementOutput {
  std::string name;
  Vector6 mean_force = Vector6::Zero();
  Vector6 rms_force = Vector6::Zero();
};

/// @brief One periodic solution of the gear system.
struct SystemNhbPoint {
  double mesh_frequency_hz = 0.0;
  NhbPoint point;  ///< the engine's point (harmonics of u; omega = 2π f_m)
  std::vector<SystemNhbMeshOutput> meshes;
  std::vector<SystemNhbElementOutput> elements;  ///< empty unless compute_element_forces
  /// (N × (H+1)) one-sided harmonics Q_k of q [m, rad] (q = Q_0 + 2 Re Σ Q_k e^{ikωt}, ω = Ω/p),
  /// recovered as T D_k⁻¹(F_k − P_zᵀ N_k); empty unless keep_response.
  MatrixXc response;
};

/// @brief A fold or jump of the traced curve, in mesh frequency (coordinate 0 = first mesh δ_η).
struct SystemNhbJump {
  bool up_sweep = true;            ///< seen by an increasing-frequency sweep
  double mesh_frequency_hz = 0.0;  ///< [Hz]
  double rms_dte_before = 0.0;     ///< RMS DTE of the first mesh before the jump [m]
  double rms_dte_after = 0.0;      ///< after (NaN when no landing branch was traced) [m]
  /// RMS DTE on every stable branch at the jump frequency, nearest first (NhbJump::
  /// rms_landings: with several, the transient decides which one a sweep lands on) [m].
  std::vector<double> rms_dte_landings;
};

/// @brief The traced frequency-response curve.
struct SystemNhbCurve {
  std::vector<SystemNhbPoint> points;  ///< in arclength order
  std::vector<double> fold_frequencies_hz;
  /// Estimated |error| of each fold frequency from locating it (NhbFold::omega_error) [Hz].
  std::vector<double> fold_errors_hz;
  std::vector<SystemNhbJump> jumps;
  int harmonics_used = 0;   ///< H
  int period_multiple = 1;  ///< p (base frequency ω_m/p)
  /// Asymptotes [Hz] of branches growing without bound (NhbCurve::unbounded_branches; each
  /// warning gives the linear model's nearest parametric-instability edge); empty when none.
  std::vector<double> unbounded_branches_hz;
  Summary summary;  ///< engine summary plus the problem's warnings
};

/// @brief Traces the steady-state response over [start_hz, end_hz] (see the @file).
/// @throws InvalidInput on invalid options (H below the mesh harmonic p·P included) or an
/// unsupported model.
SystemNhbCurve TraceSystemNonlinearHb(const SystemModel& model, const SystemNhbOptions& options);

/// @brief The periodic solution at one mesh frequency from the contact-branch guess (H from
/// options.hb as in SolveNonlinearHarmonicBalance).
/// @throws InvalidInput on f_m ≤ 0 or non-finite, invalid options (H below the mesh harmonic
/// p·P included) or an unsupported model.
SystemNhbPoint SolveSystemNonlinearHb(const SystemModel& model, double mesh_frequency_hz,
                                      const SystemNhbOptions& options, Summary* summary = nullptr);

}  // namespace geardyn
