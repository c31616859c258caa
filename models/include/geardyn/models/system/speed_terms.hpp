/// @file
/// @brief The speed-dependent terms of a scene's equations: the gyroscopic moments of the spinning
/// gears and, for a planetary set with a rotating carrier, the Coriolis (gyroscopic) and
/// centripetal terms of its coordinates in the carrier frame (Cooley & Parker 2012, "Vibration
/// properties of high-speed planetary gears with gyroscopic effects", J. Vib. Acoust. 134,
/// 061014). With every body speed proportional to the reference speed s (the operating point's
/// body, Scene::GearSpeed: Ω_b = a_b s), the free vibration about the operating point is
/// \f[ M\ddot q + (C̄ + s\,G_1)\dot q + (K̄ + s^2 K_2)\, q = 0, \f]
/// G_1 skew-symmetric, K_2 symmetric (both per unit reference speed, rad/s).
///
/// **Frames.** geardyn's coordinates of a planetary set are those of Lin & Parker's model: the
/// planets sit at fixed angles ψ_n, i.e. the frame of the set is the carrier's (it rotates at
/// Ω_c). Every other body's frame is space-fixed (Ω_f = 0). A body b of polar inertia J,
/// diametral inertia I_d and mass m spinning at Ω_b, its small motion written in a frame turning
/// at Ω_f about z (complex coordinates x + iy and θx + iθy; derivation: the inertial equations
/// m ẍ_I = F, J_d φ̈_I − iJΩ_b φ̇_I = T with φ_I = φ e^{iΩ_f t}):
/// \f[ m(\ddot u + 2iΩ_f \dot u − Ω_f^2 u) = F, \qquad
///     I_d \ddot φ + i(2 I_d Ω_f − J Ω_b)\dot φ + (J Ω_b Ω_f − I_d Ω_f^2) φ = T. \f]
/// For Ω_f = Ω_c these are Cooley & Parker's G = m[[0,−2],[2,0]] and K_Ω = m I on the
/// translations of every member of the set (their Eq. (1)), with their tilts added for the 6-DOF
/// model; for Ω_f = 0 the tilt term is the classical rotor gyroscopic moment −iJΩ_b φ̇ (forward and
/// backward whirl). In real coordinates a gyroscopic coefficient g puts −g on (x, y) and +g on
/// (y, x) of G (θx, θy likewise); the stiffness terms are diagonal. z and θz have none.
///
/// **Preload of the planet bearings.** In the carrier frame a planet's centrifugal force m_p Ω_c²
/// a_w (a_w the centre distance) is carried by its bearing as a radial preload P. The linear
/// coordinates are exact positions, and the carrier pin's position is second order in the
/// carrier's rotations θ (½[(θ·r)θ − |θ|² r], r = a_w e_r), so the preloaded bearing adds the
/// geometric stiffness ½ P a_w (θz² + (θ·e_t)²) (e_t the planet's tangential direction): P a_w on
/// the carrier's θz and P a_w e_t e_tᵀ on its tilts, per planet. Without it the centripetal term
/// −m_p Ω_c² on the planets' tangential motion would make the free rotation of the drive train (the
/// carrier turning with its planets) a spurious divergence; with it that rotation stays a zero mode
/// at every speed (its energy −½ m_p Ω_c² a_w² δ² + ½ P a_w δ² = 0).
///
/// **Exactness.** The carrier frame turns the space-fixed supports of the central members into
/// rotating ones; their stiffness stays constant only when it is isotropic (k_x = k_y, k_θx =
/// k_θy, no cross terms, the same for damping), and a member coupled laterally to a body outside
/// the set (whose frame does not rotate) would see a stiffness that turns with the carrier.
/// BuildSpeedTerms refuses both with InvalidInput naming the bearing or the bodies, so that the
/// constant-coefficient equations above are exact. Not modelled: gyroscopic moments of shaft
/// nodes other than gears (a shaft's own distributed polar inertia).
#pragma once

#include <string>
#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/models/scene/scene.hpp"
#include "geardyn/models/system/scene_system.hpp"

namespace geardyn {

/// @brief Which speed-dependent terms BuildSpeedTerms includes.
struct SpeedTermsOptions {
  /// The carrier-frame terms of planetary sets (Coriolis and centripetal; see the @file).
  bool carrier_frame = true;
  /// The gyroscopic moments of the spinning gears (tilts; J Ω_b terms).
  bool spin_gyroscopics = true;
};

/// @brief G_1 and K_2 of the @file on the model's DOFs, per unit reference speed.
struct SpeedTerms {
  MatrixX gyroscopic;  ///< (n × n) G_1, skew-symmetric [N·s²/m, N·m·s² per rad/s of reference]
  MatrixX stiffness;   ///< (n × n) K_2, symmetric [N·s²/m, N·m·s²] (K̄ + s² K_2)
  /// Carrier speed per unit reference speed a_c of each planetary set with a rotating carrier
  /// (Ω_c = a_c s), in Scene::planetaries order (0 for a fixed carrier).
  std::vector<double> carrier_speed_factors;
  /// What was modelled, for the report (e.g. "carrier frame of planetary set 'stage'").
  std::vector<std::string> notes;
};

/// @brief The speed terms of `scene` on the DOFs of `built.model` (see the @file).
/// @param[in] k_bar, c_bar the model's mean K̄ and C̄ (AssembleMeanSystemMatrices, dense n × n):
///   the lateral coupling check reads them.
/// @throws InvalidInput when a set with a rotating carrier has an anisotropic support of a member
///   (naming the bearing and the entries) or a member coupled in x, y, θx or θy to a body outside
///   the set (naming both bodies); when the reference body does not reach a gear.
SpeedTerms BuildSpeedTerms(const Scene& scene, const SceneSystem& built, const MatrixX& k_bar,
                           const MatrixX& c_bar, const SpeedTermsOptions& options = {});

/// @brief a_c = Ω_c / s of the first planetary set whose carrier rotates.
/// @throws InvalidInput when the scene has no planetary set ("a carrier speed needs a planetary
///   set") or every set's carrier is its fixed member.
double CarrierSpeedFactor(const Scene& scene);

}  // namespace geardyn
