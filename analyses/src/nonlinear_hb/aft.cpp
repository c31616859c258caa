/// @file
/// @brief Alternating frequency–time kernel of NhbSolver: FFTW plans made once, harmonics →
/// samples (c2r), samples → harmonics (r2c), and the Fourier coefficients of ∂g/∂u that form
/// the Toeplitz Jacobian.
#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <numbers>
#include <utility>

#include "geardyn/common/check.hpp"
#include "geardyn/numerics/fftw_planner.hpp"
#include "nonlinear_hb/solver_impl.hpp"

namespace geardyn {

NhbSolver::Impl::Impl(NhbProblem problem_in, const NhbOptions& options_in, int harmonics)
    : problem(std::move(problem_in)),
      options(options_in),
      cached_omega(std::numeric_limits<double>::quiet_NaN()) {
  // The FFTW buffers and plans are raw: a throw after they are made (a law without the form it
  // needs, bad sizes, bad_alloc) would skip ~Impl and leak them (LeakSanitizer).
  try {
    Construct(harmonics);
  } catch (...) {
    ReleaseFftw();
    throw;
  }
}

void NhbSolver::Impl::Construct(int harmonics) {
  n = problem.law->num_coordinates();
  dofs = static_cast<int>(problem.mass.rows());
  H = harmonics;
  p = options.period_multiple;
  {
    const bool has_form = problem.law->PiecewiseLinearForm(&form);
    // The projected form (slice meshes) when the separable one is not given.
    const bool has_projected = !has_form && problem.law->ProjectedForm(p, &pform);
    exact =
        options.force_integration == NhbForceIntegration::kExact ||
        (options.force_integration == NhbForceIntegration::kAuto && (has_form || has_projected));
    GEARDYN_THROW_UNLESS(!exact || has_form || has_projected,
                         "force_integration: exact integration needs a law with a "
                         "piecewise-linear form (NhbNonlinearLaw::PiecewiseLinearForm or "
                         "ProjectedForm)");
    projected = exact && !has_form;
  }
  S = NhbSolver::SamplesFor(options, H, exact);
  m = n * (2 * H + 1);

  time_buf = fftw_alloc_real(static_cast<size_t>(S));
  freq_buf = fftw_alloc_complex(static_cast<size_t>(S / 2 + 1));
  // FFTW_ESTIMATE: planning does not touch the buffers and takes microseconds.
  {
    const std::lock_guard<std::mutex> lock(FftwPlannerMutex());
    r2c = fftw_plan_dft_r2c_1d(S, time_buf, freq_buf, FFTW_ESTIMATE);
    c2r = fftw_plan_dft_c2r_1d(S, freq_buf, time_buf, FFTW_ESTIMATE);
  }

  phase.resize(S);
  for (int s = 0; s < S; ++s) phase[s] = p * 2.0 * std::numbers::pi * s / S;
  u.resize(n, S);
  g.resize(n, S);
  dg.resize(n * n, S);
  g_h.resize(n, H + 1);
  dg_h.assign(2 * H + 1, MatrixXc::Zero(n, n));
  jacobian_coefficients.resize((4 * H + 1) * n * n);
  uncondensed = problem.IsUncondensed();
  pole_residue =
      !uncondensed && options.condensation == NhbCondensation::kAuto && BuildPoleResidueForm();
  mass_c = problem.mass.cast<std::complex<double>>();
  damping_c = problem.damping.cast<std::complex<double>>();
  stiffness_c = problem.stiffness.cast<std::complex<double>>();
  Z.assign(H + 1, MatrixXc::Zero(n, n));
  dZ = Z;
  F.assign(H + 1, VectorXc::Zero(n));
  dF = F;
  sw.resize(n, S);
  {
    // Probe whether the law locates its contact switches (optional virtual).
    MatrixX probe_u = MatrixX::Zero(n, 1), probe_v(n, 1);
    const VectorX probe_phase = VectorX::Zero(1);
    has_switch_function = problem.law->SwitchFunction(probe_u, probe_phase, probe_v);
  }
  if (projected) {
    GEARDYN_THROW_UNLESS(pform.linear.rows() == n && pform.linear.cols() == n,
                         "law: projected form: linear part is not " << n << "×" << n);
    for (const NhbProjectedTerm& t : pform.terms) {
      GEARDYN_THROW_UNLESS(t.direction.size() == n && t.breakpoints.size() >= 1 &&
                               t.weights.size() == t.breakpoints.size() &&
                               t.ramp_slopes.size() == t.ramp_points.size() &&
                               t.ramp_sides.size() == t.ramp_points.size(),
                           "law: projected form: term sizes do not match (n = " << n << ")");
    }
    u_slope.resize(n, S);
  } else if (exact) {
    const size_t count = static_cast<size_t>(n);
    GEARDYN_THROW_UNLESS(
        form.modulation.rows() == n && form.modulation.cols() >= 1 && form.slope.size() == n &&
            form.offset.size() == n && form.ramp_points.size() == count &&
            form.ramp_slopes.size() == count,
        "law: piecewise-linear form sizes do not match its " << n << " coordinates");
    for (size_t i = 0; i < count; ++i) {
      GEARDYN_THROW_UNLESS(
          form.ramp_points[i].size() == form.ramp_slopes[i].size(),
          "law: piecewise-linear form of coordinate " << i << " has unpaired ramps");
    }
    kappa_order = p * static_cast<int>(form.modulation.cols() - 1);
    const int P = kappa_order;
    u_slope.resize(n, S);
    u_full.resize(2 * H + 1);
    kappa.resize(2 * P + 1);
    ramp_product.resize(2 * (H + P) + 1);
    set_integrals.resize(2 * (2 * H + P) + 1);
    q_re.resize(ramp_product.size());
    q_im.resize(ramp_product.size());
    integrals_re.resize(set_integrals.size());
    integrals_im.resize(set_integrals.size());
  }
  J.resize(m, m);
  R.resize(m);
  dx.resize(m);
  x_trial.resize(m);
  R_trial.resize(m);
  lu = Eigen::PartialPivLU<MatrixX>(m);
}

NhbSolver::Impl::~Impl() { ReleaseFftw(); }

void NhbSolver::Impl::ReleaseFftw() {
  {
    const std::lock_guard<std::mutex> lock(FftwPlannerMutex());
    if (r2c) fftw_destroy_plan(r2c);
    if (c2r) fftw_destroy_plan(c2r);
  }
  fftw_free(time_buf);
  fftw_free(freq_buf);
  r2c = c2r = nullptr;
  time_buf = nullptr;
  freq_buf = nullptr;
}

// u(t_s) = U_0 + Σ_{k=1..H} (U_k e^{ikωt_s} + c.c.): the unnormalised FFTW c2r of the one-sided
// coefficients, zero above H.
void NhbSolver::Impl::Synthesize(const VectorX& x) {
  for (int i = 0; i < n; ++i) {
    std::fill(&freq_buf[0][0], &freq_buf[0][0] + 2 * (S / 2 + 1), 0.0);
    freq_buf[0][0] = x[Re(0, i)];
    for (int k = 1; k <= H; ++k) {
      freq_buf[k][0] = x[Re(k, i)];
      freq_buf[k][1] = x[Im(k, i)];
    }
    fftw_execute(c2r);  // destroys freq_buf, refilled on the next call
    for (int s = 0; s < S; ++s) u(i, s) = time_buf[s];
  }
}

// N_k = (1/S) Σ_s g(t_s) e^{−ikωt_s}, k = 0..H.
void NhbSolver::Impl::AnalyseForce() {
  const double inv = 1.0 / S;
  for (int i = 0; i < n; ++i) {
    for (int s = 0; s < S; ++s) time_buf[s] = g(i, s);
    fftw_execute(r2c);
    for (int k = 0; k <= H; ++k) g_h(i, k) = {freq_buf[k][0] * inv, freq_buf[k][1] * inv};
  }
}

// G_j = (1/S) Σ_s ∂g/∂u(t_s) e^{−ijωt_s}, j = 0..2H (needs S ≥ 4H + 2, checked by the options).
void NhbSolver::Impl::AnalyseJacobian() {
  const double inv = 1.0 / S;
  for (int e = 0; e < n * n; ++e) {
    const int a = e % n;
    const int b = e / n;
    for (int s = 0; s < S; ++s) time_buf[s] = dg(e, s);
    fftw_execute(r2c);
    for (int j = 0; j <= 2 * H; ++j) dg_h[j](a, b) = {freq_buf[j][0] * inv, freq_buf[j][1] * inv};
  }
}

int NhbSolver::SamplesFor(const NhbOptions& options, int harmonics, bool exact) {
  // Exact integration samples only to bracket the switches and extrema (Hermite bound).
  const int S = std::max(64, (exact ? 4 : options.samples_per_harmonic) * harmonics);
  return S + S % 2;
}

}  // namespace geardyn
