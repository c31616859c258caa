/// @file
/// @brief Analytic contact-line mesh parameters K(θ), h(θ), μ(θ) of a gear pair (spec 01 §3,
/// §4.1) and the θ-coefficients built from them (geardyn/system/coefficient.hpp).
///
/// **Model (spec 01 §4.1).** The zone of action is the rectangle g_α × B in the plane of action
/// (g_α the length of the path of contact, B = 2b the face width, b the HALF face width used in
/// κ = h/b and μ). The contact lines are straight, inclined at the base helix angle β_b, one
/// transverse base pitch p_bt apart, and move one base pitch per 2π of mesh phase θ. Each line is
/// clipped to the rectangle; with a stiffness per unit contact length k that is piecewise linear
/// along the path of contact (constant, piecewise constant or piecewise linear — e.g. a
/// single-tooth stiffness profile), the length and the first and second σ-moments of every
/// clipped piece are integrated in closed form (no quadrature):
/// \f[ K = \sum\int k\,d\ell,\quad K h = \sum\int k\sigma\,d\ell,\quad
///     K \mu b^2 = \sum\int k\sigma^2\,d\ell \f]
/// (B–S Eq. (18), (21e), (26b); for one uniformly loaded line of length F centred at h,
/// μ = κ² + F²/(12 b²)).
///
/// **Coordinates and sign conventions (for the mesh-frame code).**
/// * x̂ — roll direction: along the path of contact, the direction the contact moves (from the
///   start of contact at the driving pinion's root toward its tip; T1→T2, the spec's +v).
///   The roll coordinate x [m] is measured from the reference point p0 (the pitch point at mid
///   face, where the mesh Jacobian G is taken); the zone spans x ∈ [x_s, x_s + g_α) with
///   x_s = −g_α/2 − pitch_point_offset.
/// * ŷ — face direction: along the gear axis (the spec's w = +Z); y [m] from mid face,
///   y ∈ [−b, b].
/// * Contact line j is {x + y tan β_b = x_j}, with x_j(θ) = (θ/2π + j)·p_bt its roll position at
///   mid face: at θ = 0 a contact line passes through p0, and θ increases as the contact moves.
/// * Tooth normal in the plane of action: η = cos β_b x̂ + sin β_b ŷ (perpendicular to the lines).
/// * ζ = s·(x̂ × ŷ), the plane-of-action normal of the mesh frame, with s = zone.drive_sign
///   (spec 01 §2: x̂ = v, ŷ = w and v × w = s·u, so ζ = u).
/// * σ̂ = ζ × η = s·(−sin β_b x̂ + cos β_b ŷ): along the contact lines, pointing toward s·(+Z).
///   The coordinate of a point p on a line is its projection
///   σ = (p − p0)·σ̂ = s·(−x sin β_b + y cos β_b) = s·(y/cos β_b − x_j sin β_b).
///   This is the exact moment arm of the mesh energy (spec 01 §3): the normal approach at p is
///   δ_η(p0) − σ δ_ζ with δ_ζ = ζ·(θ_i − θ_j). For spur gears σ = s·y (the face coordinate).
///   For helical gears σ differs from the along-line distance to the face centre line
///   (s·y/cos β_b) by −s·x_j sin β_b: a line's distance from p0 along the path of contact is a
///   moment arm too (it vanishes only for the line through p0).
/// * With base_helix_angle = ψ = −s·hand·β_b and drive_sign = s, these (η, ζ, σ̂, p0) are exactly
///   mesh_frame.hpp's (eta, zeta, sigma, reference_point): h, κ here are the frame's h, κ.
///   K, L and μ do not depend on s or the sign of β_b; h flips with either.
///
/// **Channels.** The coefficient builders produce three channels that are linear in k:
/// (K, K·h, K·μ·b²) [N/m, N, N·m] = (∫k dℓ, ∫kσ dℓ, ∫kσ² dℓ). They are the entries of the mesh
/// core K2 = K[[1, −h], [−h, μb²]] = [[c0, −c1], [−c1, c2]] (spec 01 §3), so their Fourier
/// coefficients are the Hill/HB blocks directly, and linear interpolation between samples keeps
/// K2 positive semi-definite (convex combinations). Recover h = c1/c0, μ = c2/(c0 b²) with
/// MeshParametersFromChannels.
///
/// **Exactness.** For β_b = 0 and a piecewise-constant k the channels are piecewise constant in
/// θ with breakpoints where a line enters/leaves the zone or crosses a profile knot: exact steps
/// (MakePiecewiseConstantMeshCoefficient). Otherwise every channel is a continuous-or-stepwise
/// piecewise polynomial of degree ≤ 4 in θ between the breakpoints returned by Breakpoints()
/// (line ends crossing the zone corners or a knot); its Fourier coefficients are integrated
/// exactly piece by piece (MakeFourierMeshCoefficient), or it is sampled exactly
/// (MakeTableMeshCoefficient).
#pragma once

#include <string>
#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/system/coefficient.hpp"

namespace geardyn {

struct GearPairGeometry;

/// @brief The zone of action in the plane of action (see the @file conventions).
struct ZoneOfAction {
  double length = 0.0;                 ///< g_α, length of the path of contact [m], > 0
  double face_width = 0.0;             ///< B = 2b, full (common) face width [m], > 0
  double transverse_base_pitch = 0.0;  ///< p_bt [m], > 0
  /// β_b [rad], signed, |β_b| < π/2: the lines are {x + y tan β_b = const} (η = cos β_b x̂ +
  /// sin β_b ŷ). 0 for spur gears.
  double base_helix_angle = 0.0;
  /// Roll distance from the middle of the zone to the reference point p0 (pitch point), positive
  /// toward the end of contact [m]; 0 puts p0 at mid zone. Affects only h of helical gears.
  double pitch_point_offset = 0.0;
  /// s = ±1, sign of the pinion's driving torque about +Z (spec 01 §2): ζ = s·(x̂ × ŷ), so the
  /// sign of σ̂ = ζ × η and of h follows the mesh frame's.
  int drive_sign = 1;

  /// b = B/2 [m], the half face width of κ = h/b and μ.
  double half_face_width() const { return 0.5 * face_width; }
  /// ε_α = g_α/p_bt [-].
  double transverse_contact_ratio() const { return length / transverse_base_pitch; }
  /// ε_β = B|tan β_b|/p_bt [-] (= B sin β/(π m_n)).
  double overlap_ratio() const;
};

/// @brief The zone of action of a pair from its geometry.
///
/// length = g_α, face_width = the common face width, p_bt, drive_sign = s; β_b signed as
/// ψ = −s·hand·|β_b| (hand = +1 for a right-hand pinion, −1 left-hand; the same ψ as
/// mesh_frame.hpp): for a right-hand pinion turning positively about +Z, a tooth's contact runs
/// further along the path at larger z, i.e. x − y tan|β_b| = const. pitch_point_offset = g_f −
/// g_α/2 with the approach length g_f = √(r_a2² − r_b2²) − r_b2 tan α_wt (external) or r_b2 tan
/// α_wt − √(r_a2² − r_b2²) (internal gear), clamped to [0, g_α].
/// @param[in] drive_sign s = ±1, the sign of the pinion's driving torque about +Z (spec 01 §2).
/// @throws InvalidInput if drive_sign is not ±1 or the geometry gives an invalid zone.
ZoneOfAction MakeZoneOfAction(const GearPairGeometry& geometry, int drive_sign = 1);

/// @brief Stiffness per unit contact length along the path of contact, k(r) [N/m per m of
/// contact line = N/m²], r = roll distance from the START of the zone of action [m].
///
/// Piecewise linear with possible jumps: segment i covers [r_i, r_{i+1}) and goes linearly from
/// start_values[i] to end_values[i]. Values are right-continuous at knots. A non-constant profile
/// must cover the zone, [r_0, r_m] ⊇ [0, g_α] (checked by ContactLineModel up to 1e-9·g_α; the
/// end segments extend linearly over such round-off).
class StiffnessProfile {
 public:
  /// k(r) = k for all r. @throws InvalidInput unless k is finite and ≥ 0.
  static StiffnessProfile Constant(double k);
  /// k = values[i] on [knots[i], knots[i+1]); knots (m+1) strictly increasing, values (m) ≥ 0.
  static StiffnessProfile PiecewiseConstant(std::vector<double> knots, std::vector<double> values);
  /// Continuous, linear between knots; knots (m+1) strictly increasing, values (m+1) ≥ 0 at them.
  static StiffnessProfile PiecewiseLinear(std::vector<double> knots, std::vector<double> values);
  /// General form; knots (m+1), start_values (m), end_values (m), all finite, values ≥ 0.
  /// @throws InvalidInput naming the offending argument and index.
  static StiffnessProfile Segments(std::vector<double> knots, std::vector<double> start_values,
                                   std::vector<double> end_values);

  /// k(r) [N/m²]; beyond the first/last knot the end segment's linear function.
  double ValueAt(double roll) const;
  /// True for a profile made by Constant() (no knots).
  bool is_constant() const { return knots_.empty(); }
  /// True when every segment has start value == end value.
  bool is_piecewise_constant() const;
  /// Number of linear segments m (1 for a constant profile).
  int num_segments() const { return static_cast<int>(start_values_.size()); }
  /// (m+1) knots r_i [m]; empty for a constant profile.
  const std::vector<double>& knots() const { return knots_; }
  /// (m) k at the start of each segment [N/m²].
  const std::vector<double>& start_values() const { return start_values_; }
  /// (m) k at the end of each segment [N/m²].
  const std::vector<double>& end_values() const { return end_values_; }

 private:
  StiffnessProfile() = default;
  std::vector<double> knots_;
  std::vector<double> start_values_;
  std::vector<double> end_values_;
};

/// @brief Sums over the clipped contact lines at one θ.
struct ContactLineIntegrals {
  double length = 0.0;         ///< L = Σ∫dℓ, total contact-line length [m]
  double stiffness = 0.0;      ///< K = Σ∫k dℓ [N/m]
  double first_moment = 0.0;   ///< K·h = Σ∫kσ dℓ [N]
  double second_moment = 0.0;  ///< K·μ·b² = Σ∫kσ² dℓ [N·m]
  int num_lines = 0;           ///< lines with positive clipped length [-]
};

/// @brief The B–S mesh parameters at one θ (spec 01 §3).
struct MeshParameters {
  double stiffness = 0.0;    ///< K [N/m]
  double load_centre = 0.0;  ///< h = ∫kσ/K [m] along σ̂ from p0 (0 when K = 0)
  double kappa = 0.0;        ///< κ = h/b [-]
  double mu = 0.0;           ///< μ = ∫kσ²/(K b²) [-] (≥ κ²; 0 when K = 0)
};

/// @brief (K, K·h, K·μ·b²) → (K, h, κ, μ) with half face width b [m] > 0 (h = κ = μ = 0 when
/// K ≤ 0, i.e. out of contact).
MeshParameters MeshParametersFromChannels(double stiffness, double first_moment,
                                          double second_moment, double half_face_width);

/// Channel indices of the coefficients built from a ContactLineModel.
inline constexpr int kMeshStiffnessChannel = 0;     ///< K [N/m]
inline constexpr int kMeshFirstMomentChannel = 1;   ///< K·h [N]
inline constexpr int kMeshSecondMomentChannel = 2;  ///< K·μ·b² [N·m]
inline constexpr int kNumMeshChannels = 3;

/// @brief A validated zone of action with a stiffness profile; evaluates the contact-line sums.
///
/// Immutable and cheap to evaluate: CalcIntegrals loops over the ≈ ε_α + ε_β + 2 lines near the
/// zone and the profile segments they cross, never allocating.
class ContactLineModel {
 public:
  /// @throws InvalidInput naming the zone field (length, face_width, transverse_base_pitch,
  ///   base_helix_angle, pitch_point_offset, drive_sign) or "profile": non-positive or
  ///   non-finite sizes, drive_sign ≠ ±1,
  ///   |β_b| ≥ π/2, total contact ratio ε_α + ε_β < 1, a profile not covering [0, g_α].
  ContactLineModel(const ZoneOfAction& zone, StiffnessProfile profile);

  /// The validated zone of action.
  const ZoneOfAction& zone() const { return zone_; }
  /// The stiffness profile k(r).
  const StiffnessProfile& profile() const { return profile_; }
  /// b = B/2 [m].
  double half_face_width() const { return b_; }
  /// True for β_b = 0.
  bool is_spur() const { return tan_ == 0.0; }
  /// True when the channels are exactly piecewise constant in θ (spur and piecewise-constant k).
  bool is_piecewise_constant() const { return is_spur() && profile_.is_piecewise_constant(); }

  /// @brief Closed-form sums over the clipped lines at mesh phase θ [rad] (any finite value).
  ContactLineIntegrals CalcIntegrals(double theta) const;
  /// @brief The same sums restricted to the σ-band σ_min ≤ σ ≤ σ_max [m] (σ along σ̂ from p0,
  /// see the @file conventions): each clipped line is clipped once more to the band. The bands
  /// of a partition of SigmaRange() add up to CalcIntegrals(θ) (up to round-off). For spur
  /// gears σ = s·y, so a band is a face strip; for helical gears a band is a strip
  /// perpendicular to the contact lines (the slices of spec 01 §4.4, geardyn/models/mesh/
  /// mesh_cores.hpp). Never allocates.
  /// @throws InvalidInput if θ or a bound is not finite.
  ContactLineIntegrals CalcIntegrals(double theta, double sigma_min, double sigma_max) const;
  /// @brief [σ_min, σ_max] [m] spanned by the zone of action: σ = s(−x sin β_b + y cos β_b)
  /// over its corners; width g_α|sin β_b| + B cos β_b (B for spur gears).
  Vector2 SigmaRange() const;
  /// @brief K, h, κ, μ at θ [rad].
  MeshParameters CalcMeshParameters(double theta) const;
  /// @brief The channels (K, K·h, K·μ·b²) at θ into out (3); never allocates.
  void CalcChannels(double theta, Eigen::Ref<VectorX> out) const;

  /// @brief θ ∈ [0, 2π) [rad], sorted, where a channel or one of its derivatives may jump: a
  /// line end (y = ±b) reaching the start or end of the zone or an interior profile knot, i.e.
  /// x_j = c ± b tan β_b for c ∈ {x_s, x_e, knots}. Breakpoints closer than 1e-12 rad are merged.
  std::vector<double> Breakpoints() const;

 private:
  struct Segment {  // profile segment in roll coordinates x, clipped to the zone
    double x_begin, x_end, k_begin, k_end;
    double KAt(double x) const {
      return k_begin + (k_end - k_begin) * (x - x_begin) / (x_end - x_begin);
    }
  };
  // Adds line x_line clipped to the zone and to the face coordinates y ∈ [y_min, y_max].
  void AddLine(double x_line, double y_min, double y_max, ContactLineIntegrals* sums) const;
  // The phase θ/2π (wrapped) and the range of line indices j that can touch the zone at θ.
  void LinesNear(double theta, double* phase, long* j_min, long* j_max) const;

  ZoneOfAction zone_;
  StiffnessProfile profile_;
  std::vector<Segment> segments_;
  double b_ = 0.0, tan_ = 0.0, cos_ = 1.0, sin_ = 0.0, sign_ = 1.0, x_start_ = 0.0, x_end_ = 0.0;
};

/// @brief Exact steps of (K, K·h, K·μ·b²) for a spur pair with piecewise-constant k: the
/// n/n+1-pair rectangular wave (levels n·k·B and (n+1)·k·B for constant k, n = ⌊ε_α⌋, the
/// (n+1)-pair level for the fraction ε_α − n of the period). Adjacent equal intervals merged.
/// @throws InvalidInput unless model.is_piecewise_constant().
PiecewiseConstantCoefficient MakePiecewiseConstantMeshCoefficient(const ContactLineModel& model);

/// @brief Fourier series of (K, K·h, K·μ·b²) with num_terms ≥ 0 harmonics, coefficients exact up
/// to round-off (each channel is a piecewise polynomial of degree ≤ 4 between Breakpoints(); it
/// is interpolated exactly at 5 Chebyshev nodes per piece and ∫τ^r e^{−izτ} is evaluated in
/// closed form). Valid for spur and helical pairs.
FourierCoefficient MakeFourierMeshCoefficient(const ContactLineModel& model, int num_terms);

/// @brief The shortest series meeting rel_tol in the error measure of ToFourierWithTolerance
/// (relative L2 tail, max over channels; variance exact by Gauss–Legendre on each piece).
FourierFit MakeFourierMeshCoefficientWithTolerance(const ContactLineModel& model, double rel_tol,
                                                   int max_terms = 4096);

/// @brief num_samples ≥ 1 exact samples θ_s = 2πs/S of (K, K·h, K·μ·b²) (linear interpolation).
TableCoefficient MakeTableMeshCoefficient(const ContactLineModel& model, int num_samples);

/// Which representation MakeMeshCoefficient returns.
enum class MeshCoefficientForm {
  kAuto,  ///< constant → Constant; spur & piecewise-constant k → steps; else Fourier
  kPiecewiseConstant,  ///< MakePiecewiseConstantMeshCoefficient (throws if not exact)
  kFourier,            ///< num_terms > 0 ? that many : by rel_tol
  kTable,              ///< num_samples exact samples
};

/// @brief Options of MakeMeshCoefficient.
struct MeshCoefficientOptions {
  MeshCoefficientForm form = MeshCoefficientForm::kAuto;  ///< representation to build
  int num_terms = 0;      ///< Fourier harmonics; 0 → the fewest meeting rel_tol
  double rel_tol = 1e-4;  ///< relative L2 tail error target of the Fourier form [-]
  int max_terms = 4096;   ///< cap on the Fourier harmonics chosen by rel_tol
  int num_samples = 256;  ///< table samples per mesh period
  /// False with a message naming the field, its value and the bound.
  bool IsValid(std::string* why) const;
};

/// @brief The mesh coefficient (K, K·h, K·μ·b²) in the requested form (see
/// MeshCoefficientForm). kAuto returns a ConstantCoefficient when all channels are constant to
/// 1e-13 relative (e.g. spur with integer ε_α), so that Classify reports kConstant.
///
/// Cost of the Fourier form: helical channels are continuous with kinks, c_n = O(n⁻²), so the
/// relative L2 error falls like N^{-3/2} (≈ 16 terms for 1e-2, 75 for 1e-3, 350 for 1e-4, 7000
/// for 1e-6 on a typical pair, docs/benchmarks.md). When rel_tol is not met within max_terms
/// the max_terms series is returned (use MakeFourierMeshCoefficientWithTolerance to see the
/// achieved error). Spur channels with a piecewise-linear k jump where lines enter and leave, so
/// both Fourier (L2 ∝ N^{-1/2}) and tables converge slowly: approximate k by many constant steps
/// instead, which keeps the exact piecewise-constant path.
/// @throws InvalidInput if options are invalid.
Coefficient MakeMeshCoefficient(const ContactLineModel& model,
                                const MeshCoefficientOptions& options = {});

}  // namespace geardyn
