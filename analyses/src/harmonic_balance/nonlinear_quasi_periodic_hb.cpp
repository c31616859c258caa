// Nonlinear harmonic balance on the torus of several mesh frequencies
// (nonlinear_quasi_periodic_hb.hpp): condensation per order κ, AFT with FFTW's d-dimensional
// transforms, Newton with the exact Jacobian of the sampled residual.
#include "geardyn/analyses/nonlinear_quasi_periodic_hb.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <iomanip>
#include <memory>
#include <numbers>
#include <sstream>
#include <variant>

#include "geardyn/common/check.hpp"
#include "system_nhb/mesh_force_law.hpp"
#include "system_nhb/system_problem.hpp"
#include "torus_fft.hpp"
#include "torus_harmonics.hpp"

namespace geardyn {
namespace {

using Complex = std::complex<double>;
using internal::HarmonicSet;
using internal::MeshForceLaw;
using internal::MeshForceTerm;
using internal::TorusFft;

constexpr std::int64_t kMaxGridPoints = std::int64_t{1} << 22;

std::string FormatG(double x) {
  std::ostringstream s;
  s << std::setprecision(3) << x;
  return s.str();
}

int GridSize(const NonlinearQuasiPeriodicHbOptions& options, int d) {
  const int H = options.torus.total_order;
  if (options.torus.samples_per_base > 0) return options.torus.samples_per_base;
  int N = 32;
  while (N < 8 * H) N *= 2;
  const auto points = [&](int s) {
    std::int64_t p = 1;
    for (int b = 0; b < d; ++b) p *= s;
    return p;
  };
  while (N / 2 > 2 * H && points(N) > kMaxGridPoints) N /= 2;
  return N;
}

double GridPoints(int N, int d) {
  double p = 1.0;
  for (int b = 0; b < d; ++b) p *= N;
  return p;
}

// Dense Newton matrix and LU, D_κ factors, grid arrays of u, g̃, ∂g̃/∂u and outputs.
double EstimateBytes(int n_u, int n_z, int d, int H, int N) {
  const double half = 0.5 * (static_cast<double>(CountQuasiPeriodicHarmonics(d, H)) + 1.0);
  const double rows = n_u * (2.0 * half - 1.0);
  const double grid = GridPoints(N, d);
  return 16.0 * rows * rows + 16.0 * half * n_z * n_z + 16.0 * grid * (3.0 * n_u + 8.0);
}

bool IsHalfOrder(const std::vector<int>& kappa) {
  for (int v : kappa) {
    if (v != 0) return v > 0;
  }
  return true;  // κ = 0
}

// One base: its law on its meshes' coordinates and the law phase of every grid point.
struct BaseLaw {
  std::shared_ptr<MeshForceLaw> law;
  std::vector<int> rows;  // global coordinate of each local one
  VectorX phase;          // θ_s = P_b ψ_b(s) / r_b [rad] (MeshPhase then gives r_k θ + φ_k)
  MatrixX u, force, jacobian;
};

class Solver {
 public:
  Solver(const SystemModel& model, double f_m, const NonlinearQuasiPeriodicHbOptions& options,
         NonlinearQuasiPeriodicHbResult* result);
  // Newton from x; true when converged (x holds the solution).
  bool Newton(VectorX* x, int* iterations, double* residual);
  VectorX FromCoordinateHarmonics(const MatrixXc& U) const;
  VectorX LinearGuess() const;
  VectorX ContactGuess() const;
  void Outputs(const VectorX& x);

  int unknowns() const { return n_u_ * (2 * half_count() - 1); }
  int half_count() const { return static_cast<int>(half_.size()); }

 private:
  // Re rows/columns of coordinate c at half index h (Im = Re + n_u for h > 0).
  int Re(int h, int c) const { return h == 0 ? c : n_u_ * (2 * h - 1) + c; }
  int Im(int h, int c) const { return n_u_ * (2 * h - 1) + n_u_ + c; }
  // Two-sided coefficients of every coordinate over S (n_u × |S|).
  MatrixXc TwoSided(const VectorX& x) const;
  // u samples, law evaluation (force and Jacobian of every base law at the grid).
  void EvaluateLaw(const VectorX& x);
  // r(x) (after EvaluateLaw(x)); *force_scale = max ‖N_κ‖∞.
  VectorX Residual(const VectorX& x, double* force_scale);
  MatrixX Jacobian();

  const SystemModel& model_;
  const NonlinearQuasiPeriodicHbOptions& options_;
  NonlinearQuasiPeriodicHbResult* result_;
  SystemNhbProblem sp_;
  std::vector<MeshForceTerm> terms_;
  int d_ = 0, H_ = 0, n_u_ = 0, n_z_ = 0;
  HarmonicSet set_;
  std::vector<int> half_;                 // indices into set_ of S⁺ (half_[0] = κ = 0)
  std::vector<int> mirror_;               // set_ index of −κ for every set_ index
  std::vector<std::int64_t> grid_index_;  // per set_ index
  // Grid indices of κ_h − κ_h' and κ_h + κ_h' for every pair of half indices (h·|S⁺| + h').
  std::vector<std::int64_t> difference_index_, sum_index_;
  VectorX w_;                                        // w_κ per set_ index [rad/s]
  std::vector<MatrixXc> Z_;                          // per half index (n_u × n_u)
  std::vector<VectorXc> F_tilde_;                    // per half index (n_u)
  std::vector<Eigen::PartialPivLU<MatrixXc>> D_lu_;  // per half index
  std::vector<VectorXc> F_;                          // per half index (N_z): F_κ
  std::unique_ptr<TorusFft> fft_;
  std::vector<BaseLaw> bases_;
  MatrixX u_samples_, g_samples_;
  std::vector<std::vector<Complex>> g_coefficients_;  // per coordinate, grid coefficients
  double f_tilde_scale_ = 0.0;
};

Solver::Solver(const SystemModel& model, double f_m, const NonlinearQuasiPeriodicHbOptions& options,
               NonlinearQuasiPeriodicHbResult* result)
    : model_(model),
      options_(options),
      result_(result),
      sp_(internal::BuildSystemNhbProblem(model)),
      set_(1, 0) {
  QuasiPeriodicHbResult& torus = result->torus;
  torus.bases = FindQuasiPeriodicBases(model, f_m, options.torus);
  torus.mesh_frequency_hz = f_m;
  torus.total_order = H_ = options.torus.total_order;
  d_ = static_cast<int>(torus.bases.size());
  internal::CheckOrderCoversMeshFrequencies(model, torus.bases, H_,
                                            "NonlinearQuasiPeriodicHbOptions::torus.total_order");
  terms_ = dynamic_cast<const MeshForceLaw&>(*sp_.problem.law).terms();
  n_u_ = sp_.problem.law->num_coordinates();
  n_z_ = static_cast<int>(sp_.problem.mass.rows());
  for (const std::string& w : sp_.warnings) torus.summary.warnings.push_back(w);
  const int N = GridSize(options, d_);
  torus.samples_per_base = N;
  const double bytes = EstimateBytes(n_u_, n_z_, d_, H_, N);
  GEARDYN_THROW_UNLESS(bytes <= options.torus.memory_limit_bytes,
                       "NonlinearQuasiPeriodicHbOptions::torus.total_order: H = "
                           << H_ << " on " << d_ << " base frequencies ("
                           << CountQuasiPeriodicHarmonics(d_, H_) << " harmonics of " << n_u_
                           << " nonlinear coordinates) would need about " << FormatG(bytes / 1e9)
                           << " GB (limit " << FormatG(options.torus.memory_limit_bytes / 1e9)
                           << " GB); lower the total order");
  GEARDYN_THROW_UNLESS(GridPoints(N, d_) <= 4.0 * kMaxGridPoints,
                       "NonlinearQuasiPeriodicHbOptions::torus.samples_per_base: the AFT grid of "
                           << N << "^" << d_ << " points exceeds " << 4 * kMaxGridPoints
                           << "; lower samples_per_base or the total order");
  set_ = HarmonicSet(d_, H_);
  const int S = set_.size();
  torus.orders.resize(d_, S);
  w_.resize(S);
  fft_ = std::make_unique<TorusFft>(d_, N);
  grid_index_.resize(static_cast<std::size_t>(S));
  mirror_.resize(static_cast<std::size_t>(S));
  for (int i = 0; i < S; ++i) {
    const std::vector<int>& k = set_.order(i);
    double w = 0.0;
    std::vector<int> minus(k.size());
    for (int b = 0; b < d_; ++b) {
      torus.orders(b, i) = k[static_cast<std::size_t>(b)];
      w += k[static_cast<std::size_t>(b)] * 2.0 * std::numbers::pi *
           torus.bases[static_cast<std::size_t>(b)].frequency_hz;
      minus[static_cast<std::size_t>(b)] = -k[static_cast<std::size_t>(b)];
    }
    w_(i) = w;
    grid_index_[static_cast<std::size_t>(i)] = fft_->Index(k);
    mirror_[static_cast<std::size_t>(i)] = set_.Find(minus);
  }
  const int zero = set_.Find(std::vector<int>(static_cast<std::size_t>(d_), 0));
  half_.push_back(zero);
  for (int i = 0; i < S; ++i) {
    if (i != zero && IsHalfOrder(set_.order(i))) half_.push_back(i);
  }
  const std::size_t hc = half_.size();
  difference_index_.resize(hc * hc);
  sum_index_.resize(hc * hc);
  for (std::size_t h = 0; h < hc; ++h) {
    for (std::size_t hp = 0; hp < hc; ++hp) {
      const std::vector<int>& k = set_.order(half_[h]);
      const std::vector<int>& kp = set_.order(half_[hp]);
      difference_index_[h * hc + hp] = fft_->Index(k, kp, -1);
      sum_index_[h * hc + hp] = fft_->Index(k, kp, +1);
    }
  }

  // Loads: f0 at κ = 0, f1/2 at κ = P_b e_b of the base of ratio 1 (ω_m = P_b Ω_b).
  int unit_base = -1;
  for (int b = 0; b < d_; ++b) {
    if (std::abs(torus.bases[static_cast<std::size_t>(b)].phase_ratio - 1.0) <=
        std::max(options.torus.ratio_tolerance, 1e-12)) {
      unit_base = b;
    }
  }
  const bool has_f1 = sp_.problem.force_amplitude.size() > 0 &&
                      sp_.problem.force_amplitude.cwiseAbs().maxCoeff() > 0.0;
  GEARDYN_THROW_UNLESS(!has_f1 || unit_base >= 0,
                       "quasi-periodic nonlinear harmonic balance: the model has harmonic loads "
                       "at the phase of ratio 1, but no mesh runs at ratio 1");
  int f1_index = -1;
  if (has_f1) {
    std::vector<int> k(static_cast<std::size_t>(d_), 0);
    const std::int64_t P = torus.bases[static_cast<std::size_t>(unit_base)].period_meshes;
    if (P <= H_) {
      k[static_cast<std::size_t>(unit_base)] = static_cast<int>(P);
      f1_index = set_.Find(k);
    } else {
      torus.summary.warnings.push_back("the harmonic loads (at order " + std::to_string(P) +
                                       " of their base) lie above the total order " +
                                       std::to_string(H_) + " and are left out");
    }
  }

  // Condensation per κ ∈ S⁺.
  const MatrixX& M = sp_.problem.mass;
  const MatrixX& C = sp_.problem.damping;
  const MatrixX& K = sp_.problem.stiffness;
  const MatrixXc Pz = sp_.problem.projection.cast<Complex>();
  double min_rcond = 1.0;
  for (int h = 0; h < half_count(); ++h) {
    const int i = half_[static_cast<std::size_t>(h)];
    const double w = w_(i);
    MatrixXc D = (K - w * w * M).cast<Complex>() + Complex(0.0, w) * C.cast<Complex>();
    D_lu_.emplace_back(D);
    min_rcond = std::min(min_rcond, D_lu_.back().rcond());
    const MatrixXc X = D_lu_.back().solve(MatrixXc(Pz.transpose()));
    const MatrixXc R = Pz * X;
    Eigen::PartialPivLU<MatrixXc> r_lu(R);
    min_rcond = std::min(min_rcond, r_lu.rcond());
    Z_.push_back(r_lu.inverse());
    VectorXc F = VectorXc::Zero(n_z_);
    if (h == 0) F = sp_.problem.force_mean.cast<Complex>();
    if (i == f1_index) F = 0.5 * sp_.problem.force_amplitude;
    F_.push_back(F);
    F_tilde_.push_back(Z_.back() * (Pz * D_lu_.back().solve(F)));
    f_tilde_scale_ = std::max(f_tilde_scale_, F_tilde_.back().cwiseAbs().maxCoeff());
  }
  if (!(min_rcond > 1e-14)) {
    torus.summary.warnings.push_back(
        "ill-conditioned condensation (estimated 1/cond " + FormatG(min_rcond) +
        "): an undamped mode at a combination frequency of the bases?");
  }

  // One law per base on its meshes' coordinates; its phase per grid point.
  std::vector<int> base_of(static_cast<std::size_t>(model.num_meshes()), 0);
  for (int b = 0; b < d_; ++b) {
    for (int k : torus.bases[static_cast<std::size_t>(b)].meshes) {
      base_of[static_cast<std::size_t>(k)] = b;
    }
  }
  bases_.resize(static_cast<std::size_t>(d_));
  std::vector<std::vector<MeshForceTerm>> base_terms(static_cast<std::size_t>(d_));
  for (const MeshForceTerm& t : terms_) {
    const int b = base_of[static_cast<std::size_t>(t.mesh)];
    MeshForceTerm local = t;
    local.first = static_cast<int>(bases_[static_cast<std::size_t>(b)].rows.size());
    for (int c = 0; c < t.count; ++c)
      bases_[static_cast<std::size_t>(b)].rows.push_back(t.first + c);
    base_terms[static_cast<std::size_t>(b)].push_back(local);
  }
  const std::int64_t points = fft_->points();
  for (int b = 0; b < d_; ++b) {
    BaseLaw& base = bases_[static_cast<std::size_t>(b)];
    if (base.rows.empty()) continue;
    base.law = std::make_shared<MeshForceLaw>(model, base_terms[static_cast<std::size_t>(b)]);
    const QuasiPeriodicBase& qb = torus.bases[static_cast<std::size_t>(b)];
    base.phase.resize(points);
    for (std::int64_t p = 0; p < points; ++p) {
      base.phase(p) = static_cast<double>(qb.period_meshes) * fft_->Angle(p, b) / qb.phase_ratio;
    }
  }
  u_samples_.resize(n_u_, points);
  g_samples_.resize(n_u_, points);
  g_coefficients_.assign(static_cast<std::size_t>(n_u_),
                         std::vector<Complex>(static_cast<std::size_t>(points)));
  torus.summary.counters["unknowns"] = unknowns();
  torus.summary.counters["harmonics"] = S;
  torus.summary.counters["bases"] = d_;
  torus.summary.counters["grid_points"] = static_cast<long>(points);
  torus.summary.counters["nonlinear_coordinates"] = n_u_;
}

MatrixXc Solver::TwoSided(const VectorX& x) const {
  MatrixXc U = MatrixXc::Zero(n_u_, set_.size());
  for (int h = 0; h < half_count(); ++h) {
    const int i = half_[static_cast<std::size_t>(h)];
    for (int c = 0; c < n_u_; ++c) {
      const Complex v = h == 0 ? Complex(x(Re(h, c)), 0.0) : Complex(x(Re(h, c)), x(Im(h, c)));
      U(c, i) = v;
      U(c, mirror_[static_cast<std::size_t>(i)]) = std::conj(v);
    }
  }
  return U;
}

VectorX Solver::FromCoordinateHarmonics(const MatrixXc& U) const {
  GEARDYN_THROW_UNLESS(U.rows() == n_u_ && U.cols() == set_.size(),
                       "quasi-periodic nonlinear harmonic balance: the initial guess has "
                           << U.rows() << " x " << U.cols() << " harmonics; this model and "
                           << "total order need " << n_u_ << " x " << set_.size());
  VectorX x = VectorX::Zero(unknowns());
  for (int h = 0; h < half_count(); ++h) {
    const int i = half_[static_cast<std::size_t>(h)];
    for (int c = 0; c < n_u_; ++c) {
      x(Re(h, c)) = U(c, i).real();
      if (h > 0) x(Im(h, c)) = U(c, i).imag();
    }
  }
  return x;
}

void Solver::EvaluateLaw(const VectorX& x) {
  const MatrixXc U = TwoSided(x);
  std::vector<Complex> row(static_cast<std::size_t>(set_.size()));
  VectorX samples(fft_->points());
  for (int c = 0; c < n_u_; ++c) {
    for (int i = 0; i < set_.size(); ++i) row[static_cast<std::size_t>(i)] = U(c, i);
    fft_->Synthesize(grid_index_, row.data(), samples.data());
    u_samples_.row(c) = samples.transpose();  // a row of a column-major matrix is strided
  }
  for (BaseLaw& base : bases_) {
    if (!base.law) continue;
    base.u.resize(static_cast<Eigen::Index>(base.rows.size()), fft_->points());
    for (std::size_t r = 0; r < base.rows.size(); ++r) base.u.row(r) = u_samples_.row(base.rows[r]);
    base.law->Evaluate(base.u, base.phase, base.force, base.jacobian);
    for (std::size_t r = 0; r < base.rows.size(); ++r)
      g_samples_.row(base.rows[r]) = base.force.row(r);
  }
}

VectorX Solver::Residual(const VectorX& x, double* force_scale) {
  VectorX r(unknowns());
  std::vector<double> samples(static_cast<std::size_t>(fft_->points()));
  double scale = 0.0;
  for (int c = 0; c < n_u_; ++c) {
    for (std::int64_t p = 0; p < fft_->points(); ++p)
      samples[static_cast<std::size_t>(p)] = g_samples_(c, p);
    fft_->Analyze(samples.data(), g_coefficients_[static_cast<std::size_t>(c)].data());
  }
  for (int h = 0; h < half_count(); ++h) {
    const int i = half_[static_cast<std::size_t>(h)];
    VectorXc U(n_u_), Nk(n_u_);
    for (int c = 0; c < n_u_; ++c) {
      U(c) = h == 0 ? Complex(x(Re(h, c)), 0.0) : Complex(x(Re(h, c)), x(Im(h, c)));
      Nk(c) = g_coefficients_[static_cast<std::size_t>(c)]
                             [static_cast<std::size_t>(grid_index_[static_cast<std::size_t>(i)])];
    }
    scale = std::max(scale, Nk.cwiseAbs().maxCoeff());
    const VectorXc res =
        Z_[static_cast<std::size_t>(h)] * U + Nk - F_tilde_[static_cast<std::size_t>(h)];
    for (int c = 0; c < n_u_; ++c) {
      r(Re(h, c)) = res(c).real();
      if (h > 0) r(Im(h, c)) = res(c).imag();
    }
  }
  if (force_scale != nullptr) *force_scale = scale;
  return r;
}

MatrixX Solver::Jacobian() {
  const int R = unknowns();
  MatrixX J = MatrixX::Zero(R, R);
  // Linear part: Z_κ U_κ.
  for (int h = 0; h < half_count(); ++h) {
    const MatrixXc& Z = Z_[static_cast<std::size_t>(h)];
    for (int a = 0; a < n_u_; ++a) {
      for (int c = 0; c < n_u_; ++c) {
        if (h == 0) {
          J(Re(0, a), Re(0, c)) += Z(a, c).real();
          continue;
        }
        J(Re(h, a), Re(h, c)) += Z(a, c).real();
        J(Re(h, a), Im(h, c)) -= Z(a, c).imag();
        J(Im(h, a), Re(h, c)) += Z(a, c).imag();
        J(Im(h, a), Im(h, c)) += Z(a, c).real();
      }
    }
  }
  // Law: ∂N_κ/∂U_κ' = Ĵ_{κ−κ'}, per mesh term (∂g̃/∂u is block diagonal by mesh).
  std::vector<double> samples(static_cast<std::size_t>(fft_->points()));
  std::vector<Complex> coefficients(static_cast<std::size_t>(fft_->points()));
  for (const BaseLaw& base : bases_) {
    if (!base.law) continue;
    const int nb = static_cast<int>(base.rows.size());
    for (const MeshForceTerm& t : base.law->terms()) {
      for (int jc = 0; jc < t.count; ++jc) {
        for (int ic = 0; ic < t.count; ++ic) {
          const int li = t.first + ic, lj = t.first + jc;  // local row, column
          for (std::int64_t p = 0; p < fft_->points(); ++p) {
            samples[static_cast<std::size_t>(p)] = base.jacobian(lj * nb + li, p);
          }
          fft_->Analyze(samples.data(), coefficients.data());
          const int a = base.rows[static_cast<std::size_t>(li)];
          const int c = base.rows[static_cast<std::size_t>(lj)];
          const int hc = half_count();
          for (int h = 0; h < hc; ++h) {
            for (int hp = 0; hp < hc; ++hp) {
              const std::size_t pair = static_cast<std::size_t>(h) * static_cast<std::size_t>(hc) +
                                       static_cast<std::size_t>(hp);
              const Complex gm = coefficients[static_cast<std::size_t>(difference_index_[pair])];
              if (hp == 0) {
                J(Re(h, a), Re(0, c)) += gm.real();
                if (h > 0) J(Im(h, a), Re(0, c)) += gm.imag();
                continue;
              }
              const Complex gp = coefficients[static_cast<std::size_t>(sum_index_[pair])];
              const Complex da = gm + gp;
              const Complex db = Complex(0.0, 1.0) * (gm - gp);
              J(Re(h, a), Re(hp, c)) += da.real();
              J(Re(h, a), Im(hp, c)) += db.real();
              if (h > 0) {
                J(Im(h, a), Re(hp, c)) += da.imag();
                J(Im(h, a), Im(hp, c)) += db.imag();
              }
            }
          }
        }
      }
    }
  }
  return J;
}

bool Solver::Newton(VectorX* x, int* iterations, double* residual) {
  const double tol = options_.newton_tolerance;
  double force_scale = 0.0;
  EvaluateLaw(*x);
  VectorX r = Residual(*x, &force_scale);
  double norm = r.lpNorm<Eigen::Infinity>();
  *iterations = 0;
  for (int it = 0; it < options_.max_newton_iterations; ++it) {
    if (!std::isfinite(norm)) break;
    if (norm <= tol * (1.0 + f_tilde_scale_ + force_scale)) {
      *residual = norm;
      return true;
    }
    ++*iterations;
    const MatrixX J = Jacobian();
    Eigen::PartialPivLU<MatrixX> lu(J);
    const VectorX dx = lu.solve(-r);
    if (!dx.allFinite()) break;
    // Backtracking on ‖r‖∞: halve until it decreases (at most 7 times, then take the step).
    double alpha = 1.0;
    VectorX trial, r_trial;
    double trial_norm = 0.0, trial_scale = 0.0;
    for (int cut = 0; cut < 8; ++cut) {
      trial = *x + alpha * dx;
      EvaluateLaw(trial);
      r_trial = Residual(trial, &trial_scale);
      trial_norm = r_trial.lpNorm<Eigen::Infinity>();
      if (trial_norm < (1.0 - 1e-4 * alpha) * norm) break;
      alpha *= 0.5;
    }
    *x = trial;
    r = r_trial;
    norm = trial_norm;
    force_scale = trial_scale;
  }
  *residual = norm;
  return std::isfinite(norm) && norm <= tol * (1.0 + f_tilde_scale_ + force_scale);
}

VectorX Solver::ContactGuess() const {
  MatrixX Kc;
  VectorX gc;
  sp_.problem.law->ContactBranch(Kc, gc);
  VectorX x = VectorX::Zero(unknowns());
  for (int h = 0; h < half_count(); ++h) {
    VectorXc rhs = F_tilde_[static_cast<std::size_t>(h)];
    if (h == 0) rhs -= gc.cast<Complex>();
    const VectorXc U = Z_[static_cast<std::size_t>(h)].partialPivLu().solve(rhs);
    for (int c = 0; c < n_u_; ++c) {
      x(Re(h, c)) = U(c).real();
      if (h > 0) x(Im(h, c)) = U(c).imag();
    }
  }
  return x;
}

VectorX Solver::LinearGuess() const {
  QuasiPeriodicHbOptions linear = options_.torus;
  linear.samples_per_base = 0;
  QuasiPeriodicHbResult qp;
  try {
    qp = SolveQuasiPeriodicHb(model_, result_->torus.mesh_frequency_hz, linear);
  } catch (const InvalidInput&) {
    return VectorX();  // e.g. the linear solver's memory bound: no guess from it
  }
  if (!qp.summary.ok() || qp.harmonics.cols() != set_.size()) return VectorX();
  const int n = model_.num_dofs();
  MatrixX P(n_u_, n);
  for (int c = 0; c < n_u_; ++c) {
    const SystemMesh& mesh =
        model_.meshes()[static_cast<std::size_t>(sp_.coordinate_mesh[static_cast<std::size_t>(c)])];
    P.row(c) =
        internal::ScatteredMeshRow(mesh, sp_.coordinate_channel[static_cast<std::size_t>(c)], n);
  }
  return FromCoordinateHarmonics(P.cast<Complex>() * qp.harmonics);
}

void Solver::Outputs(const VectorX& x) {
  QuasiPeriodicHbResult& torus = result_->torus;
  const int S = set_.size();
  const int n = model_.num_dofs();
  EvaluateLaw(x);
  Residual(x, nullptr);  // g_coefficients_ at the solution
  result_->coordinate_harmonics = TwoSided(x);
  // Response of every DOF: Q_κ = T D_κ⁻¹ (F_κ − P_zᵀ N_κ) (+ the static part at κ = 0).
  torus.harmonics = MatrixXc::Zero(n, S);
  const MatrixXc PzT = sp_.problem.projection.transpose().cast<Complex>();
  for (int h = 0; h < half_count(); ++h) {
    const int i = half_[static_cast<std::size_t>(h)];
    VectorXc Nk(n_u_);
    for (int c = 0; c < n_u_; ++c) {
      Nk(c) = g_coefficients_[static_cast<std::size_t>(c)]
                             [static_cast<std::size_t>(grid_index_[static_cast<std::size_t>(i)])];
    }
    const VectorXc z =
        D_lu_[static_cast<std::size_t>(h)].solve(F_[static_cast<std::size_t>(h)] - PzT * Nk);
    VectorXc q = sp_.reduction.cast<Complex>() * z;
    if (h == 0) q += sp_.static_response.cast<Complex>();
    torus.harmonics.col(i) = q;
    torus.harmonics.col(mirror_[static_cast<std::size_t>(i)]) = q.conjugate();
  }
  // Per mesh: DTE = δ_η − ε_η and F_η on the grid.
  const std::int64_t points = fft_->points();
  std::vector<double> samples(static_cast<std::size_t>(points));
  std::vector<Complex> coefficients(static_cast<std::size_t>(points));
  const int zero = half_[0];
  double max_rms = 0.0, tail_sq = 0.0;
  const int tail_order = (3 * H_) / 4;
  torus.meshes.assign(static_cast<std::size_t>(model_.num_meshes()), QuasiPeriodicMeshOutput{});
  result_->contact.assign(static_cast<std::size_t>(model_.num_meshes()),
                          NonlinearQuasiPeriodicMeshContact{});
  for (int k = 0; k < model_.num_meshes(); ++k) {
    torus.meshes[static_cast<std::size_t>(k)].name =
        model_.meshes()[static_cast<std::size_t>(k)].name;
  }
  for (int b = 0; b < d_; ++b) {
    for (int k : torus.bases[static_cast<std::size_t>(b)].meshes) {
      torus.meshes[static_cast<std::size_t>(k)].base = b;
    }
    BaseLaw& base = bases_[static_cast<std::size_t>(b)];
    if (!base.law) continue;
    const internal::MeshForceSamples ms = base.law->SampleMeshForces(base.u, base.phase);
    for (const MeshForceTerm& t : base.law->terms()) {
      QuasiPeriodicMeshOutput& out = torus.meshes[static_cast<std::size_t>(t.mesh)];
      NonlinearQuasiPeriodicMeshContact& contact =
          result_->contact[static_cast<std::size_t>(t.mesh)];
      const Eigen::Index row = t.mesh;
      // DTE samples and coefficients.
      for (std::int64_t p = 0; p < points; ++p) {
        samples[static_cast<std::size_t>(p)] = base.u(t.first, p) - ms.te_eta(row, p);
      }
      fft_->Analyze(samples.data(), coefficients.data());
      const Eigen::Map<const VectorX> dte(samples.data(), points);
      out.mean_dte = dte.mean();
      out.rms_dte = std::sqrt((dte.array() - out.mean_dte).square().mean());
      out.peak_to_peak_dte = dte.maxCoeff() - dte.minCoeff();
      double tail = 0.0, largest = 0.0;
      for (int i = 0; i < S; ++i) {
        if (i == zero) continue;
        const Complex D =
            coefficients[static_cast<std::size_t>(grid_index_[static_cast<std::size_t>(i)])];
        int norm = 0;
        for (int v : set_.order(i)) norm += std::abs(v);
        if (norm > tail_order) tail += std::norm(D);
        largest = std::max(largest, std::abs(D));
      }
      max_rms = std::max(max_rms, out.rms_dte);
      tail_sq = std::max(tail_sq, tail);
      for (int i = 0; i < S; ++i) {
        if (i == zero || w_(i) < 0.0 || (w_(i) == 0.0 && !IsHalfOrder(set_.order(i)))) continue;
        const Complex D =
            coefficients[static_cast<std::size_t>(grid_index_[static_cast<std::size_t>(i)])];
        if (std::abs(D) <= 1e-12 * largest) continue;
        out.lines.push_back({set_.order(i), w_(i) / (2.0 * std::numbers::pi), 2.0 * std::abs(D)});
      }
      std::sort(out.lines.begin(), out.lines.end(),
                [](const QuasiPeriodicLine& a, const QuasiPeriodicLine& c) {
                  return a.amplitude > c.amplitude;
                });
      // Force and contact.
      const VectorX force = ms.force_eta.row(row).transpose();
      out.mean_force = force.mean();
      out.rms_force = std::sqrt((force.array() - out.mean_force).square().mean());
      out.peak_to_peak_force = force.maxCoeff() - force.minCoeff();
      contact.min_force = force.minCoeff();
      contact.max_force = force.maxCoeff();
      contact.contact_loss_fraction = 1.0 - ms.drive_loaded.row(row).mean();
      contact.back_contact = ms.back_loaded.row(row).maxCoeff() > 0.0;
    }
  }
  torus.summary.error_estimate = max_rms > 0.0 ? std::sqrt(tail_sq) / max_rms : 0.0;
}

}  // namespace

bool NonlinearQuasiPeriodicHbOptions::IsValid(std::string* why) const {
  std::ostringstream msg;
  std::string inner;
  if (!torus.IsValid(&inner)) {
    msg << "NonlinearQuasiPeriodicHbOptions::torus: " << inner;
  } else if (!(std::isfinite(newton_tolerance) && newton_tolerance >= 1e-14 &&
               newton_tolerance <= 1e-3)) {
    msg << "NonlinearQuasiPeriodicHbOptions::newton_tolerance: must be in [1e-14, 1e-3], got "
        << newton_tolerance;
  } else if (max_newton_iterations < 1 || max_newton_iterations > 1000) {
    msg << "NonlinearQuasiPeriodicHbOptions::max_newton_iterations: must be in [1, 1000], got "
        << max_newton_iterations;
  }
  if (why != nullptr) *why = msg.str();
  return msg.str().empty();
}

double EstimateNonlinearQuasiPeriodicHbBytes(const SystemModel& model,
                                             const NonlinearQuasiPeriodicHbOptions& options) {
  std::string why;
  GEARDYN_THROW_UNLESS(options.IsValid(&why), why);
  const int d = static_cast<int>(FindQuasiPeriodicBases(model, 1.0, options.torus).size());
  const SystemNhbProblem sp = internal::BuildSystemNhbProblem(model);
  return EstimateBytes(sp.problem.law->num_coordinates(), static_cast<int>(sp.problem.mass.rows()),
                       d, options.torus.total_order, GridSize(options, d));
}

NonlinearQuasiPeriodicHbResult SolveNonlinearQuasiPeriodicHb(
    const SystemModel& model, double mesh_frequency_hz,
    const NonlinearQuasiPeriodicHbOptions& options, const MatrixXc* initial) {
  const auto t0 = std::chrono::steady_clock::now();
  GEARDYN_THROW_UNLESS(std::isfinite(mesh_frequency_hz) && mesh_frequency_hz > 0.0,
                       "quasi-periodic nonlinear harmonic balance: mesh frequency must be finite "
                       "and > 0 Hz, got "
                           << mesh_frequency_hz);
  std::string why;
  GEARDYN_THROW_UNLESS(options.IsValid(&why), why);
  NonlinearQuasiPeriodicHbResult result;
  Solver solver(model, mesh_frequency_hz, options, &result);
  std::vector<std::pair<std::string, VectorX>> guesses;
  if (initial != nullptr) guesses.emplace_back("caller", solver.FromCoordinateHarmonics(*initial));
  guesses.emplace_back("linear", VectorX());
  guesses.emplace_back("contact", VectorX());
  Summary& summary = result.torus.summary;
  bool converged = false;
  int total_iterations = 0;
  VectorX x;
  for (auto& [name, guess] : guesses) {
    if (name == "linear") guess = solver.LinearGuess();
    if (name == "contact") guess = solver.ContactGuess();
    if (guess.size() == 0) continue;
    x = guess;
    int iterations = 0;
    converged = solver.Newton(&x, &iterations, &result.residual_norm);
    total_iterations += iterations;
    if (converged) {
      result.initial_guess = name;
      break;
    }
  }
  result.newton_iterations = total_iterations;
  summary.counters["newton_iterations"] = total_iterations;
  if (!converged) {
    summary.status = Status::kNotConverged;
    summary.message = "quasi-periodic nonlinear harmonic balance: Newton did not converge at " +
                      FormatG(mesh_frequency_hz) + " Hz (residual " +
                      FormatG(result.residual_norm) + " N after " +
                      std::to_string(total_iterations) +
                      " iterations from every initial guess); the values are the last iterate";
  }
  if (x.size() > 0 && x.allFinite()) solver.Outputs(x);
  summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace geardyn
