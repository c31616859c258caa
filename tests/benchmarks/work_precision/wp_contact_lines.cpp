// Work-precision benchmark of the contact-line mesh parameters (spec 01 §4.1; architecture §3.10).
//
// Prints CSV `method, knob, wall_time_s, error, evaluations` (lines starting with '#' are
// comments). The reference is the analytic contact-line model (closed-form clipped-line
// integrals), which the tests check against the closed forms of L(θ) and brute-force quadrature.
//
//  * analytic / sampled_quadrature — (K, K·h, K·μ·b²) on a grid of 512 phases, the quadrature with
//    `knob` midpoint samples per line (the "obvious" slice-sum alternative). error = max over the
//    grid and channels of |Δ c_ch| / (K̄ b^ch); evaluations = point evaluations of k.
//  * fourier_exact / fourier_fft_of_table / table_linear — representations of the θ-functions with
//    `knob` harmonics (the FFT uses 4·knob samples; the table `knob` samples). error = relative L2
//    error (max over channels of ‖f − f̃‖₂/‖f − f̄‖₂) on 2^14 midpoints; evaluations = calls of
//    the analytic model needed to build the representation. fourier_exact_maxabs: the max-norm
//    error relative to K̄ b^ch.
//  * fourier_tolerance — MakeFourierMeshCoefficientWithTolerance, knob = rel_tol; error = achieved.
//  * spur_* — the spur rectangular wave: exact steps vs its Fourier series (Gibbs, N^{-1/2}).
//
// Run: build with -DCMAKE_BUILD_TYPE=Release -DGEARDYN_BUILD_BENCHMARKS=ON, then
//   ./tests/benchmarks/wp_contact_lines > wp_contact_lines.csv
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include "geardyn/common/units.hpp"
#include "geardyn/models/mesh/contact_lines.hpp"
#include "geardyn/system/coefficient.hpp"
#include "wp_common.hpp"

namespace {

using geardyn::wp::Row;
using geardyn::wp::TimeIt;

using geardyn::ContactLineModel;
using geardyn::VectorX;
constexpr double kTwoPi = 2.0 * geardyn::kPi;
constexpr double kPitch = 0.0059;  // p_bt [m]
constexpr double kFace = 0.024;    // B [m]
constexpr double kK = 1.4e10;      // k [N/m²]

geardyn::ZoneOfAction Zone(double eps_alpha, double eps_beta) {
  geardyn::ZoneOfAction z;
  z.length = eps_alpha * kPitch;
  z.face_width = kFace;
  z.transverse_base_pitch = kPitch;
  z.base_helix_angle = std::atan(eps_beta * kPitch / kFace);
  z.pitch_point_offset = 0.2 * kPitch;
  return z;
}

/// Independent sampled quadrature: `samples` midpoints per line over the face.
void SampledChannels(const geardyn::ZoneOfAction& z, const geardyn::StiffnessProfile& k,
                     double theta, int samples, double* out) {
  const double b = 0.5 * z.face_width, p = z.transverse_base_pitch, beta = z.base_helix_angle;
  const double tb = std::tan(beta), sb = std::sin(beta), cb = std::cos(beta);
  const double xs = -0.5 * z.length - z.pitch_point_offset, xe = xs + z.length;
  const double dy = 2.0 * b / samples, dl = dy / cb;
  const int j0 = static_cast<int>(std::floor((xs - b * std::abs(tb)) / p - theta / kTwoPi)) - 1;
  const int j1 = static_cast<int>(std::ceil((xe + b * std::abs(tb)) / p - theta / kTwoPi)) + 1;
  out[0] = out[1] = out[2] = 0.0;
  for (int j = j0; j <= j1; ++j) {
    const double xj = (theta / kTwoPi + j) * p;
    for (int i = 0; i < samples; ++i) {
      const double y = -b + (i + 0.5) * dy;
      const double x = xj - y * tb;
      if (x < xs || x >= xe) continue;
      const double kk = k.ValueAt(x - xs) * dl;
      const double sigma = -x * sb + y * cb;
      out[0] += kk;
      out[1] += kk * sigma;
      out[2] += kk * sigma * sigma;
    }
  }
}

/// Relative L2 error (max over channels, relative to each channel's variation) and max-abs error
/// relative to K̄ b^ch, on `points` midpoints.
void RepresentationError(const ContactLineModel& model, const geardyn::Coefficient& c,
                         double* l2_rel, double* max_rel) {
  const int points = 1 << 14;
  VectorX exact(3), approx(3), mean = VectorX::Zero(3);
  std::vector<VectorX> values(points, VectorX(3));
  for (int i = 0; i < points; ++i) {
    model.CalcChannels((i + 0.5) * kTwoPi / points, values[i]);
    mean += values[i] / points;
  }
  VectorX err2 = VectorX::Zero(3), var2 = VectorX::Zero(3), maxabs = VectorX::Zero(3);
  for (int i = 0; i < points; ++i) {
    geardyn::Evaluate(c, (i + 0.5) * kTwoPi / points, approx);
    const VectorX d = values[i] - approx;
    err2 += d.cwiseAbs2();
    var2 += (values[i] - mean).cwiseAbs2();
    maxabs = maxabs.cwiseMax(d.cwiseAbs());
  }
  *l2_rel = 0.0;
  *max_rel = 0.0;
  double scale = mean[0];
  for (int ch = 0; ch < 3; ++ch) {
    if (var2[ch] > 1e-24 * scale * scale * points) {
      *l2_rel = std::max(*l2_rel, std::sqrt(err2[ch] / var2[ch]));
    }
    *max_rel = std::max(*max_rel, maxabs[ch] / scale);
    scale *= model.half_face_width();
  }
}

}  // namespace

int main() {
  std::printf(
      "# wp_contact_lines: helical eps_alpha = 1.55, eps_beta = 1.30, tooth profile k(r)\n");
  std::printf("method,knob,wall_time_s,error,evaluations\n");
  const double g = 1.55 * kPitch;
  const geardyn::StiffnessProfile tooth = geardyn::StiffnessProfile::PiecewiseLinear(
      {0.0, 0.3 * g, 0.7 * g, g}, {0.6 * kK, kK, kK, 0.5 * kK});
  const geardyn::ZoneOfAction zone = Zone(1.55, 1.3);
  const ContactLineModel model(zone, tooth);
  const double b = model.half_face_width();

  // --- 1. pointwise: analytic vs sampled quadrature on 512 phases.
  const int grid = 512;
  std::vector<VectorX> exact(grid, VectorX(3));
  double kbar = 0.0;
  for (int i = 0; i < grid; ++i) {
    model.CalcChannels((i + 0.5) * kTwoPi / grid, exact[i]);
    kbar += exact[i][0] / grid;
  }
  {
    VectorX out(3);
    double sink = 0.0;
    const double t = TimeIt([&] {
      for (int i = 0; i < grid; ++i) {
        model.CalcChannels((i + 0.5) * kTwoPi / grid, out);
        sink += out[0];
      }
    });
    Row("analytic", 0, t, 0.0, grid);
    if (!(sink > 0.0)) return 1;
  }
  for (int samples : {8, 32, 128, 512, 2048, 8192, 32768}) {
    double out[3];
    double worst = 0.0;
    for (int i = 0; i < grid; ++i) {
      SampledChannels(zone, tooth, (i + 0.5) * kTwoPi / grid, samples, out);
      for (int ch = 0; ch < 3; ++ch) {
        worst = std::max(worst, std::abs(out[ch] - exact[i][ch]) / (kbar * std::pow(b, ch)));
      }
    }
    double sink = 0.0;
    const double t = TimeIt([&] {
      for (int i = 0; i < grid; ++i) {
        SampledChannels(zone, tooth, (i + 0.5) * kTwoPi / grid, samples, out);
        sink += out[0];
      }
    });
    const int lines =
        static_cast<int>(std::ceil(zone.transverse_contact_ratio() + zone.overlap_ratio())) + 3;
    Row("sampled_quadrature", samples, t, worst, 1.0 * grid * samples * lines);
    if (!(sink > 0.0)) return 1;
  }

  // --- 2. representations vs number of terms / samples.
  const double pieces = static_cast<double>(model.Breakpoints().size());
  for (int n : {4, 8, 16, 32, 64, 128, 256, 512, 1024}) {
    double l2 = 0.0, mx = 0.0;
    const double t = TimeIt([&] { (void)geardyn::MakeFourierMeshCoefficient(model, n); });
    const geardyn::Coefficient f = geardyn::MakeFourierMeshCoefficient(model, n);
    RepresentationError(model, f, &l2, &mx);
    Row("fourier_exact", n, t, l2, pieces * 5);
    Row("fourier_exact_maxabs", n, t, mx, pieces * 5);
    const double t_fft = TimeIt(
        [&] { (void)geardyn::ToFourier(geardyn::MakeTableMeshCoefficient(model, 4 * n), n); });
    const geardyn::Coefficient ff =
        geardyn::ToFourier(geardyn::MakeTableMeshCoefficient(model, 4 * n), n);
    RepresentationError(model, ff, &l2, &mx);
    Row("fourier_fft_of_table", n, t_fft, l2, 4.0 * n);
    const double t_tab = TimeIt([&] { (void)geardyn::MakeTableMeshCoefficient(model, n); });
    const geardyn::Coefficient tab = geardyn::MakeTableMeshCoefficient(model, n);
    RepresentationError(model, tab, &l2, &mx);
    Row("table_linear", n, t_tab, l2, n);
  }
  for (double tol : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6}) {
    double l2 = 0.0, mx = 0.0;
    int terms = 0;
    const double t = TimeIt([&] {
      terms = geardyn::MakeFourierMeshCoefficientWithTolerance(model, tol, 1 << 14).num_terms;
    });
    const geardyn::Coefficient f =
        geardyn::MakeFourierMeshCoefficientWithTolerance(model, tol, 1 << 14).fourier;
    RepresentationError(model, f, &l2, &mx);
    std::printf("# fourier_tolerance rel_tol = %g: %d terms\n", tol, terms);
    Row("fourier_tolerance", tol, t, l2, pieces * 5);
  }

  // --- 3. spur rectangular wave: exact steps vs its Fourier series.
  const ContactLineModel spur(Zone(1.62, 0.0), geardyn::StiffnessProfile::Constant(kK));
  {
    double l2 = 0.0, mx = 0.0;
    const double t = TimeIt([&] { (void)geardyn::MakePiecewiseConstantMeshCoefficient(spur); });
    const geardyn::Coefficient steps = geardyn::MakePiecewiseConstantMeshCoefficient(spur);
    RepresentationError(spur, steps, &l2, &mx);
    Row("spur_piecewise_exact", 0, t, l2, 2);
    for (int n : {4, 16, 64, 256, 1024}) {
      const double tf = TimeIt([&] { (void)geardyn::ToFourier(steps, n); });
      RepresentationError(spur, geardyn::ToFourier(steps, n), &l2, &mx);
      Row("spur_fourier", n, tf, l2, 2);
    }
  }
  return 0;
}
