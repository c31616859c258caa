/// @file
/// @brief Campbell diagram: the modes of the speed-dependent mean system
/// \f[ M\ddot q + (C̄ + s\,G_1)\dot q + (K̄ + s^2 K_2)\, q = 0 \f]
/// over a grid of reference speeds s, tracked by mode shape, with the excitation orders, their
/// crossings with the modes and the speeds where the modes lose stability (issue 18). G_1 and K_2
/// come from the scene (speed_terms.hpp: spin gyroscopics, the carrier frame of planetary sets).
///
/// **Solve.** With M = LLᵀ and r = Lᵀq the pencil becomes K̃ = L⁻¹K̄L⁻ᵀ, G̃, C̃, K̃_2. The
/// rigid-body modes a of K̄ (its null space V_r, relative eigenvalue ≤ zero_tol) are free
/// rotations: no speed-stiffness energy (V_rᵀK̃_2V_r = 0, which the planet-bearing preload of
/// speed_terms.hpp ensures for a rotating carrier), no damping (C̃ V_r = 0) and V_rᵀG̃V_r = 0. The
/// remaining coupling V_eᵀK̃_2V_r is the O(s²) change of the rigid mode's shape (the planets ride
/// out on their bearings under the centrifugal preload, so the carrier's free rotation moves them
/// on a circle a little larger than a_w); the model is consistent to O(s²) only, and keeping that
/// coupling would leave an O(s⁴) negative stiffness on the free rotation (a spurious slow
/// divergence), so it is dropped: its effect on the elastic frequencies is O(s⁴) (second-order
/// perturbation). The rigid modes are then ignorable coordinates, eliminated exactly (Routh):
/// their equation ä + s G_re ρ̇ = 0
/// conserves the momentum ȧ + s G_re ρ (zero for free vibration), so the elastic coordinates
/// ρ (r = V_e ρ) see the extra stiffness s² G_er G_erᵀ with G_er = V_eᵀ G̃₁ V_r — in a rotating
/// carrier, the Coriolis force of the planets riding along with a speed change. The eigenvalues
/// of the full problem are those of the reduced one and the rigid modes' zeros (λ² a + λ s G_re ρ
/// = 0 gives a = −s G_re ρ/λ for λ ≠ 0). Otherwise (e.g. mass-proportional damping) nothing is
/// deflated and a warning says so. At zero speed the reduced K is diagonal and the frequencies are
/// exactly `geardyn modes`' frequencies. Each speed
/// then solves the real state-space eigenproblem of
/// \f[ A = \begin{bmatrix} 0 & ω_s I \\ −(K_ρ + s^2 K_{2ρ})/ω_s & −(C_ρ + s G_ρ)\end{bmatrix}, \f]
/// (z = [ρ; ρ̇/ω_s], ω_s = √max λ(K_ρ) balances the blocks) with Eigen's EigenSolver. Of the 2m
/// eigenvalues, one per mode is kept: those with Im λ > 0, and for the real ones (a divergent or
/// overdamped mode) the largest real parts; the frequency is Im λ/2π (0 for a real eigenvalue).
///
/// **Tracking** (modal assurance criterion on the mass-weighted displacement part ρ, complex):
/// the modes of a speed are matched to the tracks of the previous speed greedily by decreasing
/// MAC. Modes of the previous speed within cluster_rel_tol in frequency form a cluster (a
/// repeated frequency at zero speed, e.g. the translational pairs and planet modes of a planetary
/// set): a mode's MAC with the cluster is its squared projection on the cluster's span, and the
/// cluster's tracks take their modes in frequency order, so a pair that splits with speed stays
/// two tracks. A match with MAC below mac_warning is flagged (veering or a crossing of similar
/// shapes: the order of those tracks is not certain there).
///
/// **Stability.** A mode with Re λ > instability_tol·ω_s is unstable: *divergence* when λ is real
/// (a static instability, the frequency has reached zero) and *flutter* when it is complex (two
/// modes have merged). For the undamped problem the zero-frequency speeds are known in closed
/// form: K_ρ + s² K_2ρ is singular at s² = −1/μ for the negative eigenvalues μ of
/// K_ρ^{-1/2} K_2ρ K_ρ^{-1/2}; they are listed (static_critical_speeds). Beyond the first, K_eff is
/// indefinite: the system diverges unless the gyroscopic terms stabilize it (they can when an
/// even number of eigenvalues of K_eff are negative), which the eigenvalues decide.
///
/// **Excitation orders and crossings.** An excitation line is f = h·s (h in Hz per rad/s of the
/// reference speed, one per mesh order or shaft order). A crossing is a sign change of
/// f_track − h s between two grid speeds, located by linear interpolation; zero-frequency points
/// are skipped.
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/common/eigen_types.hpp"
#include "geardyn/common/summary.hpp"
#include "geardyn/system/dof_map.hpp"

namespace geardyn {

/// One excitation line f = hz_per_speed · s.
struct CampbellExcitation {
  std::string name;           ///< e.g. "mesh 'sun-planet_0' ×2", "shaft 'pinion' ×1"
  std::string kind;           ///< "mesh" or "shaft"
  int order = 1;              ///< harmonic of the mesh or shaft frequency [-]
  double hz_per_speed = 0.0;  ///< h [Hz per rad/s of the reference speed], > 0
};

/// The speed-dependent mean system (dense; n × n each).
struct CampbellProblem {
  MatrixX mass;             ///< M, symmetric positive definite
  MatrixX damping;          ///< C̄ (zero for the undamped diagram)
  MatrixX stiffness;        ///< K̄, symmetric positive semi-definite
  MatrixX gyroscopic;       ///< G_1, skew-symmetric, per unit speed
  MatrixX speed_stiffness;  ///< K_2, symmetric, per unit speed squared
  DofMap dofs;              ///< the DOFs (labels; body roles for planetary types)
  std::vector<CampbellExcitation> excitations;
};

/// Options of ComputeCampbell.
struct CampbellOptions {
  std::vector<double> speeds;     ///< reference speeds s [rad/s], ≥ 0, strictly increasing
  double zero_tol = 1e-9;         ///< rigid-body threshold, relative to max λ(K̃), in (0, 1)
  double cluster_rel_tol = 1e-6;  ///< repeated-frequency clusters for tracking, in [0, 0.1)
  double mac_warning = 0.5;       ///< matches below this MAC are flagged, in (0, 1)
  double instability_tol = 1e-8;  ///< Re λ > tol·ω_s is unstable, in (0, 1e-2)
  /// @brief True when every field is in range; otherwise `why` names the field and the bound.
  bool IsValid(std::string* why) const;
};

/// One tracked mode over the speed grid (vectors indexed by speed).
struct CampbellTrack {
  std::vector<double> frequency_hz;  ///< Im λ/2π ≥ 0 [Hz]
  std::vector<double> growth_rate;   ///< Re λ [1/s] (< 0 damped, > 0 unstable)
  std::vector<double> mac;           ///< MAC with the previous speed's match (1 at the first)
  std::vector<ModeType> labels;      ///< dominant kinetic-energy kind at each speed
  std::vector<PlanetaryModeType> planetary_labels;  ///< per speed; empty without planets
  std::vector<char> unstable;                       ///< 1 where Re λ > instability_tol·ω_s
};

/// A crossing of a track with an excitation line.
struct CampbellCrossing {
  int track = 0;
  int excitation = 0;
  double speed = 0.0;         ///< s at the crossing [rad/s]
  double frequency_hz = 0.0;  ///< h·s [Hz]
};

/// A run of consecutive grid speeds with an unstable mode of one kind (any track: the two tracks
/// of a merged flutter pair may swap from one speed to the next).
struct CampbellInstability {
  std::vector<int> tracks;       ///< the tracks unstable somewhere in the run, ascending
  std::string kind;              ///< "divergence" (real λ) or "flutter" (complex λ)
  double speed_begin = 0.0;      ///< first unstable grid speed [rad/s]
  double speed_end = 0.0;        ///< last unstable grid speed [rad/s]
  double max_growth_rate = 0.0;  ///< max Re λ over the run [1/s]
};

/// The Campbell diagram.
struct CampbellResult {
  std::vector<double> speeds;  ///< s [rad/s]
  std::vector<CampbellTrack> tracks;
  std::vector<CampbellCrossing> crossings;
  std::vector<CampbellInstability> instabilities;
  /// Speeds s > 0 where K̄ + s²K_2 is singular on the deflated space (a frequency of the undamped
  /// system is zero there), ascending [rad/s].
  std::vector<double> static_critical_speeds;
  int num_rigid_body_modes = 0;  ///< deflated zero modes of K̄
  bool deflated = false;         ///< the rigid-body modes were deflated (see the @file)
  /// Warnings (low-MAC matches, no deflation), counters ("speeds", "modes", "state_dofs").
  Summary summary;
};

/// @brief The Campbell diagram of `problem` over options.speeds (see the @file).
/// @throws InvalidInput on invalid options or matrices of mismatched sizes.
CampbellResult ComputeCampbell(const CampbellProblem& problem, const CampbellOptions& options);

}  // namespace geardyn
