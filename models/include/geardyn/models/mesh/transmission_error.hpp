/// @file
/// @brief The transmission-error channels of a gear pair: the exact integrals ∫k e dℓ and
/// ∫k σ e dℓ of the unloaded separation e (tooth_modifications.hpp) over the clipped contact
/// lines of a ContactLineModel, their θ-coefficients over the hunting period, and the
/// transmission-error pair ε(θ) = K2(θ)⁻¹ [∫ke, −∫kσe] (spec 01 §3, §4).
///
/// **Channels.** (∫k e dℓ [N], ∫k σ e dℓ [N·m]) at mesh phase θ, with the same stiffness profile
/// k, the same clipped lines and the same σ as ContactLineModel. They are what the mesh load needs
/// directly: f_mesh = Gᵀ K2 ε = Gᵀ [∫ke, −∫kσe] (spec 01 §3), linear in e and in k, so tables of
/// them interpolate consistently with the (K, K·h, K·μ·b²) channels.
///
/// **Exactness.** Along a contact line (parameter y, the face coordinate) k is linear, σ is
/// linear and e is a polynomial of degree ≤ 2 between the kinks of e_profile (relief band ends)
/// and the knots of k; the line is split there and each piece is integrated with 3-point
/// Gauss–Legendre, exact for polynomials of degree ≤ 5 (the integrands k e and k σ e have degree
/// ≤ 3 and ≤ 4). The per-tooth parts (pitch deviations, runout) are uniform on a line and add
/// e_uniform·∫k dℓ and e_uniform·∫kσ dℓ.
///
/// **Structure over θ.** Every channel is a sum over the tooth pairs n ∈ ℤ (mesh cycles, see
/// tooth_modifications.hpp) of one line's contribution, shifted: with g(τ) the integrals of the
/// single line whose mid-face roll is x = τ p_bt/2π,
///   c(θ) = Σ_n [g_mod(θ − 2πn) + e_pair(n) g_K(θ − 2πn)] + e_runout(θ) Σ_n g_K(θ − 2πn),
/// where g_mod = (∫k e_mod, ∫kσ e_mod) for e_mod = e_profile + e_lead and g_K = (∫k, ∫kσ).
/// g is a piecewise polynomial of degree ≤ 5 in τ with compact support (the pair's passage
/// through the zone), so the Fourier coefficients over the period 2πP are exact by Poisson
/// summation (MakeSeparationFourierCoefficient):
///   c_m = [P | m] ĝ_mod(m/P)/2π + ĝ_K(m/P) Â_m/(2πP) + runout terms,
/// with ĝ(ω) = ∫ g(τ) e^{−iωτ} dτ (exact, piece by piece) and Â_m = Σ_{n<P} e_pair(n) e^{−2πimn/P}
/// (non-zero only for m a multiple of P/z_1 or P/z_2); the runout terms shift the mesh harmonics
/// of (K, K·h) by ±P/z_1 and ±P/z_2.
#pragma once

#include <cstdint>
#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/models/mesh/contact_lines.hpp"
#include "geardyn/models/mesh/tooth_modifications.hpp"
#include "geardyn/system/coefficient.hpp"
#include "geardyn/system/mesh_core.hpp"

namespace geardyn {

/// Channel indices of the separation coefficients.
inline constexpr int kSeparationKeChannel = 0;       ///< ∫k e dℓ [N]
inline constexpr int kSeparationKSigmaEChannel = 1;  ///< ∫k σ e dℓ [N·m]
inline constexpr int kNumSeparationChannels = 2;
/// Channel indices of the transmission-error coefficients.
inline constexpr int kTransmissionErrorEtaChannel = 0;   ///< ε_η [m]
inline constexpr int kTransmissionErrorZetaChannel = 1;  ///< ε_ζ [rad]
inline constexpr int kNumTransmissionErrorChannels = 2;

/// @brief The sums over the clipped contact lines at one θ.
struct SeparationIntegrals {
  double stiffness = 0.0;  ///< K = Σ∫k dℓ [N/m] (the same as ContactLineModel's, to round-off)
  double first_moment = 0.0;  ///< K·h = Σ∫kσ dℓ [N]
  double k_e = 0.0;           ///< Σ∫k e dℓ [N]
  double k_sigma_e = 0.0;     ///< Σ∫k σ e dℓ [N·m]
  int num_lines = 0;          ///< lines with positive clipped length [-]
};

/// @brief One contact line's integrals without the per-tooth parts (see the @file's g).
struct LineIntegrals {
  double stiffness = 0.0;     ///< ∫k dℓ [N/m]
  double first_moment = 0.0;  ///< ∫kσ dℓ [N]
  double k_e = 0.0;           ///< ∫k (e_profile + e_lead) dℓ [N]
  double k_sigma_e = 0.0;     ///< ∫k σ (e_profile + e_lead) dℓ [N·m]
  bool in_contact = false;    ///< the clipped line has positive length
};

/// @brief A contact-line model with an unloaded separation: evaluates the separation channels and
/// the transmission-error pair.
///
/// Immutable; CalcIntegrals, CalcChannels and CalcTransmissionError never allocate. θ is the mesh
/// phase [rad], unwrapped over the hunting period: any finite value, reduced modulo 2π·P with
/// P = period_meshes(); mesh cycle m = ⌊θ/2π⌋ mod P selects the tooth pairs.
class TransmissionErrorModel {
 public:
  /// @param[in] contact_lines the zone and stiffness profile (k of the integrals and K2 of ε).
  /// @param[in] modifications flank modifications.
  /// @param[in] errors tooth-to-tooth errors.
  /// @throws InvalidInput as UnloadedSeparation (field names prefixed "modifications." or
  ///   "errors.").
  TransmissionErrorModel(ContactLineModel contact_lines, const ToothModifications& modifications,
                         const ToothErrors& errors = {});

  /// The contact-line model (K2 channels).
  const ContactLineModel& contact_lines() const { return lines_; }
  /// The separation e.
  const UnloadedSeparation& separation() const { return separation_; }
  /// P [-]: 1 without tooth-to-tooth errors, else lcm(z_1, z_2).
  std::int64_t period_meshes() const { return separation_.period_meshes(); }

  /// @brief The integrals over all clipped lines at θ [rad] (exact, see the @file).
  SeparationIntegrals CalcIntegrals(double theta) const;
  /// @brief The channels (∫ke [N], ∫kσe [N·m]) at θ [rad] into out (2); never allocates.
  void CalcChannels(double theta, Eigen::Ref<VectorX> out) const;
  /// @brief ε(θ) = K2⁻¹ [∫ke, −∫kσe] (CalcTransmissionErrorPair) with K2 from contact_lines():
  /// [ε_η [m], ε_ζ [rad]]. A uniform separation e0 gives [e0, 0].
  Vector2 CalcTransmissionError(double theta) const;
  /// @brief The single line at mid-face roll x_line [m] (the @file's g(τ), τ = 2π x_line/p_bt):
  /// exact integrals of e_profile + e_lead, no per-tooth parts. Lines are right-continuous in
  /// x_line as in ContactLineModel (a spur line is in contact for x_s ≤ x_line < x_e).
  LineIntegrals CalcLineIntegrals(double x_line) const;

  /// @brief τ [rad] (sorted, merged within 1e-12 rad) where the single-line function g(τ) may
  /// change its polynomial piece: a line end y = ±b crossing the path ends, a relief kink or a
  /// stiffness knot, i.e. 2π(c ± b tan β_b)/p_bt. g vanishes outside [front, back].
  std::vector<double> LineBreakpoints() const;

 private:
  ContactLineModel lines_;
  UnloadedSeparation separation_;
  std::vector<double> roll_kinks_;  // x_s, the kinks of e_profile and k, x_e (sorted)
  double b_ = 0.0, tan_ = 0.0, cos_ = 1.0, sin_ = 0.0, sign_ = 1.0, x_start_ = 0.0, x_end_ = 0.0;
};

/// @brief S = samples_per_mesh·P exact samples θ_s = 2πs/samples_per_mesh of (∫ke, ∫kσe),
/// period_meshes = P (linear interpolation in between).
/// @param[in] samples_per_mesh ≥ 1 samples per mesh cycle; S must fit an int.
/// @throws InvalidInput naming samples_per_mesh.
TableCoefficient MakeSeparationTableCoefficient(const TransmissionErrorModel& model,
                                                int samples_per_mesh);

/// @brief The Fourier series of (∫ke, ∫kσe) over the period 2πP with num_terms harmonics
/// (harmonic m has m/P times the mesh frequency), coefficients exact to round-off (Poisson
/// summation of the single-line transform, see the @file). To resolve H mesh harmonics over the
/// hunting period pass num_terms = H·P. Cost O(num_terms · pieces of g) plus O(z) per harmonic
/// that carries pitch errors.
/// @throws InvalidInput naming num_terms (< 0).
FourierCoefficient MakeSeparationFourierCoefficient(const TransmissionErrorModel& model,
                                                    int num_terms);

/// @brief The exact Fourier coefficients c_m of (∫ke [N], ∫kσe [N·m]) over the period 2πP at the
/// given harmonics m ≥ 0 only (harmonic m has m/P times the mesh frequency; c(θ) = c_0 + 2 Re
/// Σ_{m>0} c_m e^{imθ/P}, as MakeSeparationFourierCoefficient): the same Poisson sums, without the
/// harmonics in between. What a forced response needs over a long hunting period (997/991 teeth:
/// P = 988 027): the mesh orders jP and their runout sidebands jP ± P/z, never a sampled period.
/// Cost per m: O(pieces of g) when m is a mesh order or a runout sideband, plus O(z) when pitch
/// deviations reach it; 0 otherwise.
/// @return (2 × harmonics.size()); column i is c_{harmonics[i]} (c_0 real: the mean).
/// @throws InvalidInput naming harmonics (a negative m).
MatrixXc CalcSeparationHarmonics(const TransmissionErrorModel& model,
                                 const std::vector<std::int64_t>& harmonics);

/// @brief The runout part of ε as lines (a sparse Fourier form, mesh_core.hpp): a runout is uniform
/// on every contact line, so it shifts ε by [e_runout(θ), 0] exactly (K2⁻¹[e K, −e K·h] = [e, 0]),
/// and e_runout = cos β_b [−r_e1 cos(θ/z_1 + φ_1) + r_e2 cos(θ/z_2 + φ_2)]
/// (tooth_modifications.hpp) is two lines over P_s = lcm(z_1, z_2): m = P_s/z_1 with
/// c = −cos β_b r_e1 e^{iφ_1}/2 and m = P_s/z_2 with c = cos β_b r_e2 e^{iφ_2}/2 (ε_ζ: 0).
/// Together with ε of the same separation without the runout (period 1 without pitch errors) it
/// is the exact ε of CalcTransmissionError.
/// @return empty without a runout.
/// @throws InvalidInput naming errors.pinion_teeth / errors.gear_teeth when a member with a
///   runout has fewer than 2 teeth (its line would be a mesh order: use the table).
TransmissionErrorSidebands MakeRunoutSidebands(const UnloadedSeparation& separation);

/// @brief S = samples_per_mesh·P exact samples of ε = (ε_η [m], ε_ζ [rad]) (linear interpolation).
/// @throws InvalidInput naming samples_per_mesh.
TableCoefficient MakeTransmissionErrorTableCoefficient(const TransmissionErrorModel& model,
                                                       int samples_per_mesh);

/// @brief The trigonometric interpolant of samples_per_mesh·P exact samples of ε, truncated to
/// num_terms harmonics (ToFourier of MakeTransmissionErrorTableCoefficient). ε = K2⁻¹[…] is a
/// ratio of piecewise polynomials, so its series is not exact: the error is the aliasing of the
/// samples (jumps of spur pairs decay like N^{-1/2}).
/// @throws InvalidInput naming num_terms (< 0 or ≥ samples_per_mesh·P/2) or samples_per_mesh.
FourierCoefficient MakeTransmissionErrorFourierCoefficient(const TransmissionErrorModel& model,
                                                           int num_terms, int samples_per_mesh);

}  // namespace geardyn
