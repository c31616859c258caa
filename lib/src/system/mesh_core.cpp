/// @file
/// @brief Mesh cores (spec 01 §3–§5): validation of the data forms and their allocation-free
/// kernels (K2, C2, ε, K2 ε, slice force and tangent).
#include "geardyn/system/mesh_core.hpp"

#include <atomic>
#include <cmath>
#include <complex>
#include <numbers>
#include <numeric>
#include <sstream>
#include <utility>

#include "geardyn/common/check.hpp"
#include "geardyn/common/overloaded.hpp"

namespace geardyn {
namespace {

/// Relative slack of the PSD test c0·c2 ≥ c1² on stored stiffness values: a single point load
/// has c0·c2 = c1² exactly, which sums of rounded products may miss by a few ulps.
constexpr double kPsdSlack = 1e-12;

/// The values a coefficient stores (columns): constant values, piecewise values, table samples;
/// the mean for a Fourier series (the only value that is cheap to check).
MatrixX StoredColumns(const Coefficient& coef) {
  return std::visit(Overloaded{
                        [](const ConstantCoefficient& c) -> MatrixX { return c.values(); },
                        [](const PiecewiseConstantCoefficient& c) -> MatrixX { return c.values(); },
                        [](const FourierCoefficient& c) -> MatrixX { return c.mean(); },
                        [](const TableCoefficient& c) -> MatrixX { return c.samples(); },
                    },
                    coef);
}

void CheckDamping(const MeshDamping& damping) {
  std::string why;
  GEARDYN_THROW_UNLESS(damping.IsValid(&why), why);
}

void CheckHalfFaceWidth(double b) {
  GEARDYN_THROW_UNLESS(std::isfinite(b) && b > 0.0,
                       "half_face_width: must be positive and finite, got " << b << " m");
}

std::uint64_t NextSliceCoreId() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;  // 0 is reserved for "no core"
}

}  // namespace

// ---------------------------------------------------------------------------- levels

const char* ToString(MeshCoreLevel level) {
  switch (level) {
    case MeshCoreLevel::kBlankenshipSingh:
      return "blankenship_singh";
    case MeshCoreLevel::kCoupling4Dof:
      return "coupling_4dof";
    case MeshCoreLevel::kTorsional:
      return "torsional";
  }
  return "unknown";
}

Matrix2x12 CalcLevelJacobian(MeshCoreLevel level, const Matrix2x12& G) {
  if (level != MeshCoreLevel::kTorsional) return G;
  // Translations and tilts held by rigid supports: only the rotations about the axes remain.
  Matrix2x12 G_t = Matrix2x12::Zero();
  G_t.col(5) = G.col(5);
  G_t.col(11) = G.col(11);
  return G_t;
}

// ---------------------------------------------------------------------------- damping

bool MeshDamping::IsValid(std::string* why) const {
  if (std::isfinite(value) && value >= 0.0) return true;
  if (why != nullptr) {
    std::ostringstream msg;
    msg << "damping.value: must be finite and >= 0, got " << value
        << (kind == Kind::kRatio ? " (damping ratio zeta_m [-])" : " (c_m [N*s/m])");
    *why = msg.str();
  }
  return false;
}

double ResolveDampingCoefficient(const MeshDamping& damping, double mean_stiffness,
                                 double equivalent_mass) {
  CheckDamping(damping);
  switch (damping.kind) {
    case MeshDamping::Kind::kNone:
      return 0.0;
    case MeshDamping::Kind::kCoefficient:
      return damping.value;
    case MeshDamping::Kind::kRatio:
      GEARDYN_THROW_UNLESS(
          std::isfinite(mean_stiffness) && mean_stiffness >= 0.0,
          "mean_stiffness: must be finite and >= 0, got " << mean_stiffness << " N/m");
      GEARDYN_THROW_UNLESS(
          std::isfinite(equivalent_mass) && equivalent_mass > 0.0,
          "equivalent_mass: must be positive and finite, got " << equivalent_mass << " kg");
      // c_m = 2 ζ_m √(K̄ m_e): the critical damping of the mesh mode (spec 01 §3, B–S Eq. 39).
      return 2.0 * damping.value * std::sqrt(mean_stiffness * equivalent_mass);
  }
  return 0.0;
}

// ---------------------------------------------------------------------------- LinearMeshCore

LinearMeshCore::LinearMeshCore(MeshCoreLevel level, Coefficient stiffness, double half_face_width,
                               std::optional<Coefficient> transmission_error, MeshDamping damping,
                               bool mean_lti, TransmissionErrorSidebands sidebands)
    : level_(level),
      stiffness_(std::move(stiffness)),
      half_face_width_(half_face_width),
      transmission_error_(std::move(transmission_error)),
      sidebands_(std::move(sidebands)),
      damping_(damping),
      mean_lti_(mean_lti) {
  GEARDYN_THROW_UNLESS(
      NumChannels(stiffness_) == kNumStiffnessChannels,
      "stiffness: has " << NumChannels(stiffness_) << " channels, expected 3 (K, K*h, K*mu*b^2)");
  if (transmission_error_) {
    GEARDYN_THROW_UNLESS(NumChannels(*transmission_error_) == kNumTransmissionErrorChannels,
                         "transmission_error: has " << NumChannels(*transmission_error_)
                                                    << " channels, expected 2 (eps_eta, "
                                                       "eps_zeta)");
  }
  CheckHalfFaceWidth(half_face_width_);
  CheckDamping(damping_);
  const TransmissionErrorSidebands& sb = sidebands_;
  GEARDYN_THROW_UNLESS(sb.period_meshes >= 1,
                       "sidebands.period_meshes: must be >= 1, got " << sb.period_meshes);
  GEARDYN_THROW_UNLESS(sb.coefficients.rows() == (sb.empty() ? sb.coefficients.rows() : 2) &&
                           sb.coefficients.cols() == sb.size(),
                       "sidebands.coefficients: must be 2 x " << sb.size() << " (one column per "
                                                              << "harmonic), got "
                                                              << sb.coefficients.rows() << " x "
                                                              << sb.coefficients.cols());
  GEARDYN_THROW_UNLESS(sb.coefficients.allFinite(), "sidebands.coefficients: must be finite");
  for (int i = 0; i < sb.size(); ++i) {
    const std::int64_t m = sb.harmonics[static_cast<size_t>(i)];
    GEARDYN_THROW_UNLESS(m >= 1, "sidebands.harmonics[" << i << "]: must be >= 1, got " << m);
    // A line on a harmonic of K2's period would give K2 ε a mean and mesh orders: it belongs in
    // the coefficient (CalcMeanTransmissionErrorLoad and the HB classes rely on this).
    GEARDYN_THROW_UNLESS((m * PeriodMeshes(stiffness_)) % sb.period_meshes != 0,
                         "sidebands.harmonics["
                             << i << "]: " << m << "/" << sb.period_meshes
                             << " mesh orders is a harmonic of the stiffness period "
                             << PeriodMeshes(stiffness_) << "; put it in transmission_error");
  }
  GEARDYN_THROW_UNLESS(!mean_lti_ || Classify(stiffness_) == TimeDependence::kConstant,
                       "mean_lti: the LTI level needs constant stiffness channels, got "
                           << TimeDependenceName(Classify(stiffness_))
                           << " ones (use MakeMeanLinearMeshCore)");
  // K2 = [[c0, −c1], [−c1, c2]] must be PSD at every stored value (spec 01 §6); linear
  // interpolation (tables) and steps keep that between them. All levels are checked, so bad data
  // never hides behind a reduced level.
  const MatrixX columns = StoredColumns(stiffness_);
  for (Eigen::Index k = 0; k < columns.cols(); ++k) {
    const double c0 = columns(0, k), c1 = columns(1, k), c2 = columns(2, k);
    GEARDYN_THROW_UNLESS(c0 >= 0.0 && c2 >= 0.0 && c1 * c1 <= c0 * c2 * (1.0 + kPsdSlack),
                         "stiffness: value " << k << " (K, K*h, K*mu*b^2) = (" << c0 << ", " << c1
                                             << ", " << c2
                                             << ") makes K2 indefinite (needs K >= 0, "
                                                "K*mu*b^2 >= 0 and (K*h)^2 <= K * K*mu*b^2)");
  }
}

LinearMeshCore MakeMeanLinearMeshCore(const LinearMeshCore& core) {
  return LinearMeshCore(core.level(), ConstantCoefficient(Mean(core.stiffness())),
                        core.half_face_width(), core.transmission_error(), core.damping(),
                        /*mean_lti=*/true, core.sidebands());
}

Matrix2 StiffnessCoreFromChannels(MeshCoreLevel level, const Vector3& c) {
  Matrix2 K2;
  if (level == MeshCoreLevel::kBlankenshipSingh) {
    K2 << c[0], -c[1], -c[1], c[2];  // K [[1, −h], [−h, μ b²]] (B–S Eqs. 18, 21e, 26b)
  } else {
    K2 << c[0], 0.0, 0.0, 0.0;  // κ = 0, μ term dropped (spec 01 §5)
  }
  return K2;
}

Matrix2 EvalStiffnessCore(const LinearMeshCore& core, double theta) {
  Vector3 c;
  Evaluate(core.stiffness(), theta, c);
  return StiffnessCoreFromChannels(core.level(), c);
}

Matrix2 EvalDampingCore(const LinearMeshCore& core, double theta, double c_m) {
  const Matrix2 K2 = EvalStiffnessCore(core, theta);
  // B–S Eq. (39): C2 = c_m / K · K2; an empty mesh (K = 0) has no damping either.
  if (!(K2(0, 0) > 0.0)) return Matrix2::Zero();
  return (c_m / K2(0, 0)) * K2;
}

Vector2 EvalTransmissionError(const LinearMeshCore& core, double theta) {
  Vector2 e = Vector2::Zero();
  if (core.transmission_error()) Evaluate(*core.transmission_error(), theta, e);
  const TransmissionErrorSidebands& sb = core.sidebands();
  if (!sb.empty()) {
    // 2 Re Σ c_i e^{i m_i θ/P_s}, θ reduced to one period first (θ may be ~1e7 rad).
    const double p = static_cast<double>(sb.period_meshes);
    const double phi = std::fmod(theta, 2.0 * std::numbers::pi * p) / p;
    for (int i = 0; i < sb.size(); ++i) {
      const double a = std::fmod(static_cast<double>(sb.harmonics[static_cast<size_t>(i)]) * phi,
                                 2.0 * std::numbers::pi);
      const std::complex<double> z(std::cos(a), std::sin(a));
      e(0) += 2.0 * (sb.coefficients(0, i) * z).real();
      e(1) += 2.0 * (sb.coefficients(1, i) * z).real();
    }
  }
  return e;
}

std::int64_t CoefficientPeriodMeshes(const LinearMeshCore& core) {
  std::int64_t p = PeriodMeshes(core.stiffness());
  if (core.transmission_error()) p = std::lcm(p, PeriodMeshes(*core.transmission_error()));
  return p;
}

Vector2 CalcMeanTransmissionErrorLoad(const LinearMeshCore& core, int samples_per_mesh) {
  GEARDYN_THROW_UNLESS(samples_per_mesh >= 1,
                       "samples_per_mesh: must be >= 1, got " << samples_per_mesh);
  // The sidebands' lines never meet a harmonic of K2 (constructor), so K2 ε_sb has no mean.
  if (!core.transmission_error()) return Vector2::Zero();
  const std::int64_t period = CoefficientPeriodMeshes(core);
  const std::int64_t samples = static_cast<std::int64_t>(samples_per_mesh) * period;
  Vector2 sum = Vector2::Zero();
  Vector2 e = Vector2::Zero();
  for (std::int64_t s = 0; s < samples; ++s) {
    const double theta = 2.0 * std::numbers::pi * static_cast<double>(period) *
                         static_cast<double>(s) / static_cast<double>(samples);
    Evaluate(*core.transmission_error(), theta, e);
    sum += EvalStiffnessCore(core, theta) * e;
  }
  return sum / static_cast<double>(samples);
}

Vector2 EvalTransmissionErrorLoad(const LinearMeshCore& core, double theta) {
  if (!core.has_transmission_error()) return Vector2::Zero();
  const Matrix2 K2 = EvalStiffnessCore(core, theta);
  const Vector2 e = EvalTransmissionError(core, theta);
  return K2 * e;  // f_mesh = Gᵀ K2 ε (spec 01 §3)
}

double ResolveDampingCoefficient(const LinearMeshCore& core, double equivalent_mass) {
  const double mean_k =
      core.damping().kind == MeshDamping::Kind::kRatio ? Mean(core.stiffness())[0] : 0.0;
  return ResolveDampingCoefficient(core.damping(), mean_k, equivalent_mass);
}

TimeDependence Classify(const LinearMeshCore& core) { return Classify(core.stiffness()); }

TimeDependence ClassifyExcitation(const LinearMeshCore& core) {
  if (!core.sidebands().empty()) return TimeDependence::kSmoothPeriodic;
  if (!core.transmission_error()) return TimeDependence::kConstant;
  return Combine(Classify(core.stiffness()), Classify(*core.transmission_error()));
}

std::int64_t PeriodMeshes(const LinearMeshCore& core) {
  const std::int64_t p = CoefficientPeriodMeshes(core);
  return core.sidebands().empty() ? p : std::lcm(p, core.sidebands().period_meshes);
}

// ---------------------------------------------------------------------------- SliceMeshCore

SliceMeshCore::SliceMeshCore(VectorX sigma, Coefficient stiffness, double half_face_width,
                             std::optional<Coefficient> separation, double backlash,
                             MeshDamping damping)
    : sigma_(std::move(sigma)),
      stiffness_(std::move(stiffness)),
      half_face_width_(half_face_width),
      separation_(std::move(separation)),
      backlash_(backlash),
      damping_(damping),
      id_(NextSliceCoreId()) {
  GEARDYN_THROW_UNLESS(sigma_.size() >= 1,
                       "sigma: needs at least one slice (num_slices >= 1), got 0");
  for (Eigen::Index s = 0; s < sigma_.size(); ++s) {
    GEARDYN_THROW_UNLESS(std::isfinite(sigma_[s]),
                         "sigma[" << s << "] = " << sigma_[s] << " m is not finite");
  }
  const int n = num_slices();
  GEARDYN_THROW_UNLESS(NumChannels(stiffness_) == n,
                       "stiffness: has " << NumChannels(stiffness_) << " channels but sigma has "
                                         << n << " slices (one channel per slice)");
  if (separation_) {
    GEARDYN_THROW_UNLESS(NumChannels(*separation_) == n, "separation: has "
                                                             << NumChannels(*separation_)
                                                             << " channels but sigma has " << n
                                                             << " slices (one channel per slice)");
  }
  CheckHalfFaceWidth(half_face_width_);
  GEARDYN_THROW_UNLESS(backlash_ >= 0.0,  // false for NaN; +∞ (kNoBackFlank) passes
                       "backlash: must be >= 0 [m] (or kNoBackFlank), got " << backlash_);
  CheckDamping(damping_);
  const MatrixX columns = StoredColumns(stiffness_);
  for (Eigen::Index k = 0; k < columns.cols(); ++k) {
    for (Eigen::Index s = 0; s < columns.rows(); ++s) {
      GEARDYN_THROW_UNLESS(columns(s, k) >= 0.0, "stiffness: slice " << s << " has the negative "
                                                                     << "value " << columns(s, k)
                                                                     << " N/m (value " << k << ")");
    }
  }
}

SliceMeshWorkspace::SliceMeshWorkspace(const SliceMeshCore& core)
    : stiffness(VectorX::Zero(core.num_slices())), separation(VectorX::Zero(core.num_slices())) {}

bool SliceMeshWorkspace::IsCompatibleWith(const SliceMeshCore& core) const {
  return stiffness.size() == core.num_slices() && separation.size() == core.num_slices();
}

void EvalSliceValues(const SliceMeshCore& core, SliceMeshWorkspace& ws, double theta) {
  if (ws.core_id == core.id() && ws.theta == theta) return;  // cached (NaN never matches)
  GEARDYN_THROW_UNLESS(ws.IsCompatibleWith(core),
                       "ws: workspace for " << ws.stiffness.size() << " slices used with a core of "
                                            << core.num_slices() << " slices");
  Evaluate(core.stiffness(), theta, ws.stiffness);
  if (core.separation()) {
    Evaluate(*core.separation(), theta, ws.separation);
  } else {
    ws.separation.setZero();
  }
  ws.theta = theta;
  ws.core_id = core.id();
}

SliceForce CalcSliceForce(const SliceMeshCore& core, const Eigen::Ref<const VectorX>& stiffness,
                          const Eigen::Ref<const VectorX>& separation, double delta_eta,
                          double delta_zeta) {
  const int n = core.num_slices();
  GEARDYN_THROW_UNLESS(stiffness.size() == n, "stiffness: size " << stiffness.size()
                                                                 << " does not match the " << n
                                                                 << " slices");
  GEARDYN_THROW_UNLESS(separation.size() == n || separation.size() == 0,
                       "separation: size " << separation.size() << " does not match the " << n
                                           << " slices (or 0 for none)");
  const double* k = stiffness.data();
  const double* e = separation.size() == 0 ? nullptr : separation.data();
  const double* sigma = core.sigma().data();
  const double minus_j = -core.backlash();  // −∞ without back flank: a < −j never holds
  double f0 = 0.0, f1 = 0.0, j00 = 0.0, j01 = 0.0, j11 = 0.0, energy = 0.0;
  int loaded = 0, back_loaded = 0;
  for (int s = 0; s < n; ++s) {
    const double ks = k[s];
    if (!(ks > 0.0)) continue;  // no contact line in this slice at θ
    // Approach of the slice (spec 01 §3): δ_η − σ_s δ_ζ − e_s.
    const double a = delta_eta - sigma[s] * delta_zeta - (e != nullptr ? e[s] : 0.0);
    double g = 0.0;  // clearance function g(a) = [a]₊ − [−a − j]₊
    if (a > 0.0) {
      g = a;
      ++loaded;
    } else if (a < minus_j) {
      g = a - minus_j;  // a + j < 0: the back flank pushes back
      ++back_loaded;
    } else {
      continue;  // in the backlash: no force, no stiffness
    }
    const double kg = ks * g;
    const double ks_sigma = ks * sigma[s];
    f0 += kg;
    f1 -= kg * sigma[s];
    energy += 0.5 * kg * g;
    j00 += ks;
    j01 -= ks_sigma;
    j11 += ks_sigma * sigma[s];
  }
  SliceForce out;
  out.force << f0, f1;
  out.jacobian << j00, j01, j01, j11;
  out.energy = energy;
  out.num_loaded = loaded;
  out.num_back_loaded = back_loaded;
  return out;
}

SliceForce EvalSliceForce(const SliceMeshCore& core, SliceMeshWorkspace& ws, double theta,
                          double delta_eta, double delta_zeta) {
  EvalSliceValues(core, ws, theta);
  return CalcSliceForce(core, ws.stiffness, ws.separation, delta_eta, delta_zeta);
}

Vector3 EvalSliceChannels(const SliceMeshCore& core, SliceMeshWorkspace& ws, double theta) {
  EvalSliceValues(core, ws, theta);
  Vector3 c = Vector3::Zero();
  const double* sigma = core.sigma().data();
  for (int s = 0; s < core.num_slices(); ++s) {
    const double ks = ws.stiffness[s];
    c[0] += ks;
    c[1] += ks * sigma[s];
    c[2] += ks * sigma[s] * sigma[s];
  }
  return c;
}

Matrix2 CalcSliceDampingCore(const SliceForce& force, double c_m) {
  // B–S Eq. (39) on the loaded slices: C2 = c_m / K_loaded · J.
  if (!(force.jacobian(0, 0) > 0.0)) return Matrix2::Zero();
  return (c_m / force.jacobian(0, 0)) * force.jacobian;
}

double ResolveDampingCoefficient(const SliceMeshCore& core, double equivalent_mass) {
  const double mean_k =
      core.damping().kind == MeshDamping::Kind::kRatio ? Mean(core.stiffness()).sum() : 0.0;
  return ResolveDampingCoefficient(core.damping(), mean_k, equivalent_mass);
}

TimeDependence Classify(const SliceMeshCore& /*core*/) { return TimeDependence::kNonlinear; }

std::int64_t PeriodMeshes(const SliceMeshCore& core) {
  std::int64_t p = PeriodMeshes(core.stiffness());
  if (core.separation()) p = std::lcm(p, PeriodMeshes(*core.separation()));
  return p;
}

// ---------------------------------------------------------------------------- NonlinearMeshCore

NonlinearMeshCoreOutput NonlinearMeshCore::MakeOutput() const {
  const int n = num_coordinates();
  NonlinearMeshCoreOutput out;
  out.force = VectorX::Zero(n);
  out.stiffness = MatrixX::Zero(n, n);
  out.damping = MatrixX::Zero(n, n);
  out.switching = VectorX::Zero(num_switching_functions());
  out.channels = VectorX::Zero(static_cast<Eigen::Index>(channel_names().size()));
  return out;
}

void NonlinearMeshCore::CalcForces(NonlinearMeshCoreWorkspace& ws, double theta, double theta_rate,
                                   const Eigen::Ref<const VectorX>& x,
                                   const Eigen::Ref<const VectorX>& v, bool with_jacobians,
                                   NonlinearMeshCoreOutput* out) const {
  const int n = num_coordinates();
  GEARDYN_THROW_UNLESS(std::isfinite(theta), "theta: must be finite, got " << theta);
  GEARDYN_THROW_UNLESS(std::isfinite(theta_rate), "theta_rate: must be finite, got " << theta_rate);
  GEARDYN_CHECK_SIZE(x.size(), n, "x");
  GEARDYN_CHECK_SIZE(v.size(), n, "v");
  GEARDYN_THROW_UNLESS(out != nullptr, "out: must not be null");
  GEARDYN_CHECK_SIZE(out->force.size(), n, "out->force");
  if (with_jacobians) {
    GEARDYN_THROW_UNLESS(
        out->stiffness.rows() == n && out->stiffness.cols() == n && out->damping.rows() == n &&
            out->damping.cols() == n,
        "out: stiffness and damping must be " << n << "x" << n << " (use MakeOutput())");
  }
  out->has_triplets = false;
  out->stiffness_triplets.clear();
  out->damping_triplets.clear();
  DoCalcForces(ws, theta, theta_rate, x, v, with_jacobians, out);
}

// ---------------------------------------------------------------------------- MeshCore

TimeDependence Classify(const MeshCore& core) {
  return std::visit(Overloaded{
                        [](const LinearMeshCore& c) { return Classify(c); },
                        [](const SliceMeshCore& c) { return Classify(c); },
                        [](const std::shared_ptr<const NonlinearMeshCore>&) {
                          return TimeDependence::kNonlinear;
                        },
                    },
                    core);
}

std::int64_t PeriodMeshes(const MeshCore& core) {
  return std::visit(Overloaded{
                        [](const LinearMeshCore& c) { return PeriodMeshes(c); },
                        [](const SliceMeshCore& c) { return PeriodMeshes(c); },
                        [](const std::shared_ptr<const NonlinearMeshCore>& c) {
                          GEARDYN_THROW_UNLESS(c != nullptr, "core: null NonlinearMeshCore");
                          return c->period_meshes();
                        },
                    },
                    core);
}

std::int64_t OperatorPeriodMeshes(const MeshCore& core) {
  return std::visit(
      Overloaded{
          [](const LinearMeshCore& c) {
            return c.is_mean_lti() ? std::int64_t{1} : PeriodMeshes(c.stiffness());
          },
          [](const SliceMeshCore& c) { return PeriodMeshes(c.stiffness()); },
          [&core](const std::shared_ptr<const NonlinearMeshCore>&) { return PeriodMeshes(core); },
      },
      core);
}

}  // namespace geardyn
