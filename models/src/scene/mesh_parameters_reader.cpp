// Reading [mesh.parameters]: user tables or Fourier series of K, h, μ (and ε) over one mesh
// cycle, checked (K ≥ 0, μ ≥ κ² where K > 0) and converted to the core's channels
// (K, K·h, K·μ·b²) and (ε_η, ε_ζ).
#include <algorithm>
#include <cmath>
#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "geardyn/common/units.hpp"
#include "scene/mesh_model_reader.hpp"
#include "scene/suggestions.hpp"

namespace geardyn::internal {
namespace {

using Complex = std::complex<double>;
using Numbers = std::optional<std::vector<Number>>;

/// Relative slack of the PSD test (K·h)² ≤ K·(K·μ·b²): the same as LinearMeshCore's, so data
/// accepted here is accepted by the core (μ = κ² exactly, a point load, passes).
constexpr double kPsdSlack = 1e-12;

// The values of an optional array, or `n` copies of `fill`.
std::vector<double> Values(const Numbers& a, std::size_t n, double fill) {
  std::vector<double> v(n, fill);
  if (a) {
    for (std::size_t i = 0; i < n; ++i) v[i] = (*a)[i].value;
  }
  return v;
}

// --- Fourier series [c0, a1, b1, ..., aN, bN] ----------------------------------------------------

// Two-sided complex coefficients c_{-N..N} (index n + N) of f = c0 + Σ a_n cos nθ + b_n sin nθ.
std::vector<Complex> TwoSided(const std::vector<double>& v) {
  const std::size_t terms = v.size() / 2;
  std::vector<Complex> c(2 * terms + 1);
  c[terms] = v[0];
  for (std::size_t n = 1; n <= terms; ++n) {
    const Complex cn(0.5 * v[2 * n - 1], -0.5 * v[2 * n]);
    c[terms + n] = cn;
    c[terms - n] = std::conj(cn);
  }
  return c;
}

// The two-sided coefficients of the product of two series (a convolution: exact).
std::vector<Complex> Multiply(const std::vector<Complex>& a, const std::vector<Complex>& b) {
  std::vector<Complex> c(a.size() + b.size() - 1);
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) c[i + j] += a[i] * b[j];
  }
  return c;
}

// a + scale·b for centred two-sided series of any lengths.
std::vector<Complex> AddScaled(const std::vector<Complex>& a, const std::vector<Complex>& b,
                               double scale) {
  std::vector<Complex> out(std::max(a.size(), b.size()));
  const std::size_t oa = (out.size() - a.size()) / 2, ob = (out.size() - b.size()) / 2;
  for (std::size_t i = 0; i < a.size(); ++i) out[oa + i] += a[i];
  for (std::size_t i = 0; i < b.size(); ++i) out[ob + i] += scale * b[i];
  return out;
}

// The channels (two-sided series, centred) as a FourierCoefficient (period one mesh cycle).
FourierCoefficient ToCoefficient(const std::vector<std::vector<Complex>>& channels) {
  std::size_t terms = 0;
  for (const auto& c : channels) terms = std::max(terms, c.size() / 2);
  VectorX mean(static_cast<Eigen::Index>(channels.size()));
  MatrixXc harmonics = MatrixXc::Zero(mean.size(), static_cast<Eigen::Index>(terms));
  for (std::size_t k = 0; k < channels.size(); ++k) {
    const std::size_t mid = channels[k].size() / 2;
    const auto row = static_cast<Eigen::Index>(k);
    mean[row] = channels[k][mid].real();
    for (std::size_t n = 1; n <= mid; ++n) {
      harmonics(row, static_cast<Eigen::Index>(n - 1)) = channels[k][mid + n];
    }
  }
  return FourierCoefficient(mean, harmonics);
}

double EvalSeries(const std::vector<double>& v, double theta) {
  double f = v[0];
  for (std::size_t n = 1; 2 * n < v.size(); ++n) {
    const double a = static_cast<double>(n) * theta;
    f += v[2 * n - 1] * std::cos(a) + v[2 * n] * std::sin(a);
  }
  return f;
}

// Finite values that are each in range can still overflow in the channels K·h and K·μ·b² (e.g.
// K = 3e8 N/m with μ = 1e300): found with the fuzz entry (tests/fuzz/regressions/mesh_tables/). The
// coefficient constructors would then reject an inf with a message naming neither the file nor
// the key, so the reader reports it at the key first.
void RequireFiniteChannels(const Fields& f, bool finite, bool has_mu) {
  if (finite) return;
  f.Fail(has_mu ? "mu" : "stiffness",
         std::string("the channels K*h and K*mu*b^2 overflow (not finite): K [N/m]") +
             (has_mu ? ", mu [-]" : "") + " and load_centre [m] must be of physical size");
}

double SumAbs(const std::vector<double>& v) {
  double s = 0.0;
  for (const double x : v) s += std::abs(x);
  return s;
}

}  // namespace

UserMeshParameters ReadUserMeshParameters(const Fields& f, double b, double max_load_centre) {
  f.CheckKnown({"form", "stiffness", "load_centre", "mu", "te_eta", "te_zeta"});
  const std::string form = f.ReqString(
      "form", "\"table\" (samples over one mesh cycle) or \"fourier\" ([c0, a1, b1, ...])");
  if (form != "table" && form != "fourier") {
    const std::vector<std::string> forms = {"table", "fourier"};
    f.Fail("form", "unknown form '" + form + "'" + DidYouMean(form, forms) +
                       "; forms: " + JoinNames(forms));
  }
  const bool fourier = form == "fourier";
  const Numbers stiffness = f.OptNumberArray("stiffness");
  if (!stiffness) f.Missing("stiffness", "mesh stiffness K [N/m] over one mesh cycle");
  const std::size_t n = stiffness->size();
  if (n == 0) f.Fail("stiffness", "must have at least one entry");
  if (fourier && n % 2 == 0) {
    f.Fail("stiffness",
           "a Fourier series [c0, a1, b1, ..., aN, bN] has an odd number of "
           "entries, got " +
               std::to_string(n));
  }
  const auto read = [&](std::string_view key) {
    Numbers a = f.OptNumberArray(key);
    if (a && a->size() != n) {
      f.Fail(key, "has " + std::to_string(a->size()) + " entries but stiffness has " +
                      std::to_string(n) + " (all arrays of [mesh.parameters] have one entry per " +
                      (fourier ? "coefficient" : "sample") + ")");
    }
    return a;
  };
  const Numbers h = read("load_centre");
  if (h && !fourier) {
    for (std::size_t i = 0; i < n; ++i) {
      if (std::abs((*h)[i].value) > max_load_centre) {
        f.context().Fail((*h)[i].node, f.Key("load_centre"),
                         "sample " + std::to_string(i) + ": h = " + FormatNumber((*h)[i].value) +
                             " m lies outside the zone of action (|h| <= " +
                             FormatNumber(max_load_centre) + " m; lengths are in metres)");
      }
    }
  }
  const Numbers mu = read("mu");
  const Numbers eta = read("te_eta");
  const Numbers zeta = read("te_zeta");
  const std::vector<double> k_v = Values(stiffness, n, 0.0);
  const std::vector<double> h_v = Values(h, n, 0.0);
  const std::vector<double> mu_v = Values(mu, n, 0.0);
  const double b2 = b * b;

  UserMeshParameters p;
  if (!fourier) {
    MatrixX channels(3, static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < n; ++i) {
      const auto col = static_cast<Eigen::Index>(i);
      const double k = k_v[i];
      if (k < 0.0) {
        f.context().Fail(
            (*stiffness)[i].node, f.Key("stiffness"),
            "sample " + std::to_string(i) + ": K = " + FormatNumber(k) + " N/m must be >= 0");
      }
      channels(0, col) = k;
      channels(1, col) = k * h_v[i];
      channels(2, col) = mu ? k * mu_v[i] * b2 : k * (h_v[i] * h_v[i] + b2 / 3.0);
      const double c1 = channels(1, col);
      if (k > 0.0 && c1 * c1 > k * channels(2, col) * (1.0 + kPsdSlack)) {
        const double kappa = h_v[i] / b;
        f.context().Fail(mu ? (*mu)[i].node : (*stiffness)[i].node, f.Key(mu ? "mu" : "stiffness"),
                         "sample " + std::to_string(i) + ": mu = " + FormatNumber(mu_v[i]) +
                             " is below kappa^2 = (h/b)^2 = " + FormatNumber(kappa * kappa) +
                             " (K2 would not be positive semi-definite: needs mu >= kappa^2 "
                             "where K > 0)");
      }
    }
    RequireFiniteChannels(f, channels.allFinite(), mu.has_value());
    p.stiffness = TableCoefficient(std::move(channels));
    if (eta || zeta) {
      MatrixX te(2, static_cast<Eigen::Index>(n));
      const std::vector<double> e = Values(eta, n, 0.0), z = Values(zeta, n, 0.0);
      for (std::size_t i = 0; i < n; ++i) {
        te(0, static_cast<Eigen::Index>(i)) = e[i];
        te(1, static_cast<Eigen::Index>(i)) = z[i];
      }
      p.transmission_error = TableCoefficient(std::move(te));
    }
    return p;
  }

  // Fourier: check K ≥ 0 and μ ≥ κ² at uniform points, then form the products exactly.
  const std::size_t terms = n / 2;
  const std::size_t points = std::max<std::size_t>(64, 8 * (2 * terms + 1));
  const double k_slack = 1e-12 * SumAbs(k_v);
  for (std::size_t m = 0; m < points; ++m) {
    const double theta = 2.0 * kPi * static_cast<double>(m) / static_cast<double>(points);
    const std::string where = "at check point " + std::to_string(m) + " of " +
                              std::to_string(points) + " (theta = " + FormatNumber(theta) +
                              " rad): ";
    const double k = EvalSeries(k_v, theta);
    if (k < -k_slack) {
      f.Fail("stiffness", where + "K = " + FormatNumber(k) +
                              " N/m; the series must be >= 0 over the whole mesh cycle");
    }
    const double h_m = EvalSeries(h_v, theta);
    if (std::abs(h_m) > max_load_centre) {
      f.Fail("load_centre", where + "h = " + FormatNumber(h_m) +
                                " m lies outside the zone of action (|h| <= " +
                                FormatNumber(max_load_centre) + " m; lengths are in metres)");
    }
    if (!mu || k <= k_slack) continue;
    const double kappa = h_m / b;
    const double mu_m = EvalSeries(mu_v, theta);
    if (mu_m * (1.0 + kPsdSlack) < kappa * kappa) {
      f.Fail("mu", where + "mu = " + FormatNumber(mu_m) +
                       " is below kappa^2 = (h/b)^2 = " + FormatNumber(kappa * kappa) +
                       " (K2 would not be positive semi-definite: needs mu >= kappa^2 where "
                       "K > 0)");
    }
  }
  const std::vector<Complex> K = TwoSided(k_v);
  const std::vector<Complex> Kh = Multiply(K, TwoSided(h_v));
  // K·μ·b², with the default μ = κ² + 1/3: K·h·h + K·b²/3.
  const std::vector<Complex> Kmub2 = mu ? AddScaled({}, Multiply(K, TwoSided(mu_v)), b2)
                                        : AddScaled(Multiply(Kh, TwoSided(h_v)), K, b2 / 3.0);
  const auto finite = [](const std::vector<Complex>& c) {
    return std::all_of(c.begin(), c.end(), [](const Complex& z) {
      return std::isfinite(z.real()) && std::isfinite(z.imag());
    });
  };
  RequireFiniteChannels(f, finite(K) && finite(Kh) && finite(Kmub2), mu.has_value());
  p.stiffness = ToCoefficient({K, Kh, Kmub2});
  if (eta || zeta) {
    p.transmission_error =
        ToCoefficient({TwoSided(Values(eta, n, 0.0)), TwoSided(Values(zeta, n, 0.0))});
  }
  return p;
}

}  // namespace geardyn::internal
