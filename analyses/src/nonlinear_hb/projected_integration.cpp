/// @file
/// @brief Exact Fourier coefficients, Jacobian and monodromy of a projected piecewise-linear
/// law g = L u + Σ_t k_t(θ) w_t c_t(w_tᵀ u) with piecewise-constant weights k_t
/// (nonlinear_hb.hpp, "Exact integration of projected laws"): the sets {σ(v − β) > 0} of the
/// trigonometric polynomial v = w_tᵀ u located to round-off, intersected with the weights'
/// pieces, closed-form integrals of e^{−ijθ} over them, and discrete convolutions with V.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <unsupported/Eigen/MatrixFunctions>

#include "nonlinear_hb/solver_impl.hpp"

namespace geardyn {
namespace {

using C = std::complex<double>;
constexpr double kTwoPi = 2.0 * std::numbers::pi;
/// Distinct values of ∂g/∂u whose eigen-decomposition is kept (spur slices take a few dozen:
/// the contact states of the slices times the stiffness steps); beyond, Padé per piece.
constexpr size_t kMaxPieceExponentials = 512;
/// Smallest Eigen rcond of V for exp(A'h) = V e^{Λh} V⁻¹: its round-off is ~ε/rcond ≤ 1e-10
/// relative, far below the stability margin (1e-5); below, Padé for that G.
constexpr double kMinPieceEigenvectorRcond = 1e-6;

/// Adds (k/2π) ∫_lo^hi e^{−ijθ} dθ, j = 0..J, to out[j]; inverse_j[j] = 1/j (j ≥ 1). In real
/// arithmetic: the complex products' NaN/inf branches cost as much as the products.
void AddIntervalIntegrals(double lo, double hi, double k, int J, const VectorX& inverse_j,
                          VectorXc& out) {
  const double scale = k / kTwoPi;
  out[0] += scale * (hi - lo);
  const double ca = std::cos(lo), sa = -std::sin(lo), cb = std::cos(hi), sb = -std::sin(hi);
  double ar = 1.0, ai = 0.0, br = 1.0, bi = 0.0;  // e^{−ij lo}, e^{−ij hi}
  for (int j = 1; j <= J; ++j) {
    const double ar1 = ar * ca - ai * sa, br1 = br * cb - bi * sb;
    ai = ar * sa + ai * ca;
    bi = br * sb + bi * cb;
    ar = ar1;
    br = br1;
    // (1/2π) ∫_lo^hi e^{−ijθ} dθ = (e^{−ij lo} − e^{−ij hi}) / (2π i j); d/i = (Im d, −Re d).
    const double f = scale * inverse_j[j];
    out[j] += C((ai - bi) * f, -(ar - br) * f);
  }
}

}  // namespace

void NhbSolver::Impl::IntegrateProjected(const VectorX& x) {
  // g is piecewise linear in u: on each piece g = (∂g/∂u) u + (offset), so
  //   N_k = Σ_l G_{k−l} U_l − b_k,  G_j = L δ_j + Σ_t Σ_ramps gain I_j w wᵀ,
  //   b_k = Σ_t Σ_ramps gain β I_k w   (gain = s σ),
  // one Toeplitz product for all terms instead of one convolution per term and ramp.
  SynthesizeSlope(x);
  for (MatrixXc& block : dg_h) block.setZero();
  switch_angles.clear();
  const int top = 2 * H;  // highest Jacobian harmonic
  if (inverse_j.size() != top + 1) {
    inverse_j.resize(top + 1);
    inverse_j[0] = 0.0;
    for (int j = 1; j <= top; ++j) inverse_j[j] = 1.0 / j;
  }
  MatrixXc& offsets = projected_offsets;
  offsets.setZero(n, H + 1);
  for (const NhbProjectedTerm& term : pform.terms) {
    const VectorX& w = term.direction;
    // V_m = wᵀ U_m (m = 0..H) and the samples of v and v′.
    VectorXc V = VectorXc::Zero(H + 1);
    for (int i = 0; i < n; ++i) {
      if (w[i] == 0.0) continue;
      V[0] += w[i] * x[i];
      for (int k = 1; k <= H; ++k) V[k] += w[i] * C(x[Re(k, i)], x[Im(k, i)]);
    }
    const VectorX v = u.transpose() * w, dv = u_slope.transpose() * w;
    const Eigen::Index K = term.breakpoints.size();
    for (size_t r = 0; r < term.ramp_points.size(); ++r) {
      const double sigma = term.ramp_sides[r] > 0 ? 1.0 : -1.0;
      const double beta = term.ramp_points[r];
      const double gain = term.ramp_slopes[r] * sigma;  // d/dv of s [σ(v − β)]₊ on the set
      // {σ(v − β) > 0} = {σv > σβ}.
      poly = sigma * V;
      poly_values = sigma * v;
      poly_slopes = sigma * dv;
      FindPolynomialSuperlevelSet(sigma * beta);
      if (intervals.empty()) continue;
      // Weighted set integrals I_j = (1/2π) Σ_b k_b ∫_{A ∩ piece b} e^{−ijθ} dθ. The intervals
      // start in [0, 2π) and end before start + 2π; the pieces tile the line with period 2π,
      // so shifts −2π, 0, 2π of them cover every overlap once.
      weighted_integrals.setZero(top + 1);
      for (const auto& [ta, tb] : intervals) {
        if (tb - ta < kTwoPi) {
          switch_angles.push_back(ta);
          switch_angles.push_back(tb >= kTwoPi ? tb - kTwoPi : tb);
        }
        for (Eigen::Index piece = 0; piece < K; ++piece) {
          const double lo = term.breakpoints[piece];
          const double hi =
              piece + 1 < K ? term.breakpoints[piece + 1] : term.breakpoints[0] + kTwoPi;
          const double k = term.weights[piece];
          if (k == 0.0) continue;
          for (double shift : {-kTwoPi, 0.0, kTwoPi}) {
            const double from = std::max(ta, lo + shift), to = std::min(tb, hi + shift);
            if (to > from) AddIntervalIntegrals(from, to, k, top, inverse_j, weighted_integrals);
          }
        }
      }
      for (int d = 0; d <= top; ++d) {
        const C coefficient = gain * weighted_integrals[d];
        for (int b = 0; b < n; ++b) {
          if (w[b] == 0.0) continue;
          for (int a = 0; a < n; ++a) {
            if (w[a] != 0.0) dg_h[d](a, b) += coefficient * (w[a] * w[b]);
          }
        }
      }
      if (beta != 0.0) {
        for (int k = 0; k <= H; ++k) {
          const C coefficient = gain * beta * weighted_integrals[k];
          for (int a = 0; a < n; ++a) offsets(a, k) += coefficient * w[a];
        }
      }
    }
  }
  dg_h[0] += pform.linear.cast<C>();
  // N_k = Σ_{l=−H..H} G_{k−l} U_l − b_k (G_{−j} = conj G_j, U_{−l} = conj U_l), in real
  // arithmetic on the two-sided tables: G_j at (j + 2H)n² + a + nb, U_l at (l + H)n + b.
  const int nn = n * n;
  toeplitz_g_re.resize(static_cast<size_t>((2 * top + 1) * nn));
  toeplitz_g_im.resize(toeplitz_g_re.size());
  toeplitz_u_re.resize(static_cast<size_t>((2 * H + 1) * n));
  toeplitz_u_im.resize(toeplitz_u_re.size());
  for (int j = 0; j <= top; ++j) {
    for (int e = 0; e < nn; ++e) {
      const C value = dg_h[j](e % n, e / n);
      toeplitz_g_re[static_cast<size_t>((top + j) * nn + e)] = value.real();
      toeplitz_g_im[static_cast<size_t>((top + j) * nn + e)] = value.imag();
      toeplitz_g_re[static_cast<size_t>((top - j) * nn + e)] = value.real();
      toeplitz_g_im[static_cast<size_t>((top - j) * nn + e)] = -value.imag();
    }
  }
  for (int l = 0; l <= H; ++l) {
    for (int b = 0; b < n; ++b) {
      const double re = x[Re(l, b)], im = l == 0 ? 0.0 : x[Im(l, b)];
      toeplitz_u_re[static_cast<size_t>((H + l) * n + b)] = re;
      toeplitz_u_im[static_cast<size_t>((H + l) * n + b)] = im;
      toeplitz_u_re[static_cast<size_t>((H - l) * n + b)] = re;
      toeplitz_u_im[static_cast<size_t>((H - l) * n + b)] = -im;
    }
  }
  for (int k = 0; k <= H; ++k) {
    for (int a = 0; a < n; ++a) {
      double sr = -offsets(a, k).real(), si = -offsets(a, k).imag();
      for (int l = -H; l <= H; ++l) {
        const size_t g0 = static_cast<size_t>((top + k - l) * nn + a);
        const size_t u0 = static_cast<size_t>((H + l) * n);
        for (int b = 0; b < n; ++b) {
          const double gr = toeplitz_g_re[g0 + static_cast<size_t>(n * b)];
          const double gi = toeplitz_g_im[g0 + static_cast<size_t>(n * b)];
          const double ur = toeplitz_u_re[u0 + static_cast<size_t>(b)];
          const double ui = toeplitz_u_im[u0 + static_cast<size_t>(b)];
          sr += gr * ur - gi * ui;
          si += gr * ui + gi * ur;
        }
      }
      g_h(a, k) = C(sr, si);
    }
  }
}

MatrixX NhbSolver::Impl::BalancedPieceMatrix(const MatrixX& G) const {
  const int N = dofs;
  const MatrixX Minv = problem.mass.inverse();
  MatrixX A = MatrixX::Zero(2 * N, 2 * N);
  A.topRightCorner(N, N).diagonal().setConstant(monodromy_w0);
  A.bottomLeftCorner(N, N) =
      -Minv * (problem.stiffness + problem.projection.transpose() * G * problem.projection) /
      monodromy_w0;
  A.bottomRightCorner(N, N) = -Minv * problem.damping;
  return A;
}

const NhbSolver::Impl::PieceExponential* NhbSolver::Impl::FindPieceExponential(const MatrixX& G) {
  for (const PieceExponential& e : piece_exponentials) {
    if (e.G == G) return &e;
  }
  if (piece_exponentials.size() >= kMaxPieceExponentials) return nullptr;
  PieceExponential e;
  e.G = G;
  const MatrixX A = BalancedPieceMatrix(G);
  Eigen::EigenSolver<MatrixX> es(A, true);
  if (es.info() == Eigen::Success) {
    const MatrixXc V = es.eigenvectors();
    const Eigen::PartialPivLU<MatrixXc> vlu(V);
    if (vlu.rcond() >= kMinPieceEigenvectorRcond) {
      const MatrixXc Vinv = vlu.inverse();
      e.v_re = V.real();
      e.v_im = V.imag();
      e.vinv_re = Vinv.real();
      e.vinv_im = Vinv.imag();
      e.lambda = es.eigenvalues();
      e.ok = e.lambda.allFinite() && Vinv.allFinite();
    }
  }
  piece_exponentials.push_back(std::move(e));
  return &piece_exponentials.back();
}

double NhbSolver::Impl::ProjectedMonodromyMaxMultiplier(const VectorX& x, double omega) {
  // The switches of x (the ends of every contact set) and the weights' breakpoints cut the
  // base period into pieces on which ∂g/∂u, hence A, is constant.
  ForceHarmonics(x, true);  // the switches of x (reused when the corrector just integrated x)
  std::vector<double> cuts = switch_angles;
  for (const NhbProjectedTerm& term : pform.terms) {
    for (Eigen::Index b = 0; b < term.breakpoints.size(); ++b) cuts.push_back(term.breakpoints[b]);
  }
  cuts.push_back(0.0);
  cuts.push_back(kTwoPi);
  for (double& c : cuts) c = std::clamp(c, 0.0, kTwoPi);
  std::sort(cuts.begin(), cuts.end());
  std::vector<std::pair<double, double>> pieces;
  for (size_t j = 0; j + 1 < cuts.size(); ++j) {
    if (cuts[j + 1] - cuts[j] > 1e-14 * kTwoPi) pieces.emplace_back(cuts[j], cuts[j + 1]);
  }
  // ∂g/∂u at the piece midpoints from the law itself (one batched call).
  const Eigen::Index P = static_cast<Eigen::Index>(pieces.size());
  VectorX theta(P);
  for (Eigen::Index j = 0; j < P; ++j) theta[j] = 0.5 * (pieces[j].first + pieces[j].second);
  MatrixX um, gm(n, P), dgm(n * n, P);
  SynthesizeAt(x, theta, um, nullptr);
  const VectorX ph = theta * double(p);
  problem.law->Evaluate(um, ph, gm, dgm);

  // The balanced state y = [q; q̇/ω₀] (ω₀² = ‖K‖₁/‖M‖₁): its monodromy S Φ S⁻¹ has the same
  // multipliers, and the eigenvectors of A' are far better conditioned than those of A.
  const int N = dofs;
  const double w = omega / p;
  if (!(monodromy_w0 > 0.0)) {
    const double km = problem.stiffness.cwiseAbs().colwise().sum().maxCoeff();
    const double mm = problem.mass.cwiseAbs().colwise().sum().maxCoeff();
    monodromy_w0 = km > 0.0 && mm > 0.0 && std::isfinite(km / mm) ? std::sqrt(km / mm) : 1.0;
  }
  MatrixX phi = MatrixX::Identity(2 * N, 2 * N), next(2 * N, 2 * N), E(2 * N, 2 * N);
  MatrixX scaled_re(2 * N, 2 * N), scaled_im(2 * N, 2 * N);
  MatrixX G(n, n);
  for (Eigen::Index j = 0; j < P; ++j) {
    const double h = (pieces[j].second - pieces[j].first) / w;
    G = Eigen::Map<const MatrixX>(dgm.col(j).data(), n, n);
    const PieceExponential* e = FindPieceExponential(G);
    if (e != nullptr && e->ok) {
      // exp(A'h) = Re(V e^{Λh} V⁻¹) = Re(V e^{Λh}) Re V⁻¹ − Im(V e^{Λh}) Im V⁻¹.
      for (int c = 0; c < 2 * N; ++c) {
        const std::complex<double> z = std::exp(e->lambda[c] * h);
        scaled_re.col(c) = e->v_re.col(c) * z.real() - e->v_im.col(c) * z.imag();
        scaled_im.col(c) = e->v_re.col(c) * z.imag() + e->v_im.col(c) * z.real();
      }
      E.noalias() = scaled_re * e->vinv_re;
      E.noalias() -= scaled_im * e->vinv_im;
    } else {
      E = (BalancedPieceMatrix(G) * h).exp();
    }
    next.noalias() = E * phi;
    phi.swap(next);
  }
  if (!phi.allFinite()) return std::numeric_limits<double>::quiet_NaN();
  Eigen::EigenSolver<MatrixX> es(phi, false);
  if (es.info() != Eigen::Success) return std::numeric_limits<double>::quiet_NaN();
  return es.eigenvalues().cwiseAbs().maxCoeff();
}

}  // namespace geardyn
