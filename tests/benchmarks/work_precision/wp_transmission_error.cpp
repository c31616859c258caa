// Work-precision benchmark of the transmission-error channels (spec 01 §3–4; architecture §3.10).
//
// Prints CSV `method, knob, wall_time_s, error, evaluations` (lines starting with '#' are
// comments). Scene: helical zone ε_α = 1.55, ε_β = 1.30, tooth-like stiffness profile, pinion tip
// relief (linear) and gear tip relief (parabolic), crowning and lead slope, z = 25/61 with random
// closed single pitch deviations (±3 µm) on both members and runout on both: hunting period
// P = lcm(25, 61) = 1525 mesh cycles.
//
//  * exact / sampled_quadrature — (∫ke, ∫kσe) at 512 phases spread over the hunting period: the
//    split Gauss–Legendre integrals vs a midpoint quadrature with `knob` samples per line (blind
//    to the kinks). error = max over phases of |Δ∫ke|/(K̄ e_s) and |Δ∫kσe|/(K̄ e_s b), e_s = 10 µm;
//    evaluations = point evaluations of k·e.
//  * channels_fourier_exact / channels_table_linear — representations of (∫ke, ∫kσe) over the
//    hunting period; knob = mesh harmonics H (N = H·P terms) or samples per mesh. error = relative
//    L2 error (max over channels of ‖f − f̃‖₂/‖f − f̄‖₂) on 4096 phases; evaluations = single-line
//    evaluations (Fourier) or pointwise channel evaluations (table).
//  * epsilon_table_linear / epsilon_fourier_fft — ε = (ε_η, ε_ζ) as a table with `knob` samples per
//    mesh, or as ToFourier of a table with 4·knob samples per mesh truncated to knob·P terms.
//
// Run: build with -DCMAKE_BUILD_TYPE=Release -DGEARDYN_BUILD_BENCHMARKS=ON, then
//   ./tests/benchmarks/wp_transmission_error > wp_transmission_error.csv
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <vector>

#include "geardyn/common/units.hpp"
#include "geardyn/models/mesh/transmission_error.hpp"
#include "geardyn/system/coefficient.hpp"
#include "wp_common.hpp"

namespace {

using geardyn::wp::Row;
using geardyn::wp::TimeIt;

using geardyn::TransmissionErrorModel;
using geardyn::VectorX;
constexpr double kTwoPi = 2.0 * geardyn::kPi;
constexpr double kPitch = 0.0059;  // p_bt [m]
constexpr double kFace = 0.024;    // B [m]
constexpr double kK = 1.4e10;      // k [N/m²]
constexpr double kUm = 1e-6;       // [m]
constexpr double kEps = 1.55;      // ε_α [-]

std::vector<double> ClosedPitch(int z, std::mt19937* rng) {
  std::uniform_real_distribution<double> u(-3 * kUm, 3 * kUm);
  std::vector<double> f(static_cast<size_t>(z));
  double mean = 0.0;
  for (double& v : f) {
    v = u(*rng);
    mean += v / z;
  }
  for (double& v : f) v -= mean;
  return f;
}

double KOfRoll(double r) {
  const double u = r / (kEps * kPitch);
  if (u < 0.3) return kK * (0.6 + 0.4 * u / 0.3);
  if (u < 0.7) return kK;
  return kK * (1.0 - 0.5 * (u - 0.7) / 0.3);
}

/// Independent midpoint quadrature of (∫ke, ∫kσe) with `samples` points per line over the face.
void Sampled(const TransmissionErrorModel& model, double theta, int samples, double* out) {
  const geardyn::ZoneOfAction& z = model.contact_lines().zone();
  const geardyn::UnloadedSeparation& sep = model.separation();
  const double b = 0.5 * z.face_width, p = z.transverse_base_pitch, beta = z.base_helix_angle;
  const double tb = std::tan(beta), sb = std::sin(beta), cb = std::cos(beta);
  const double xs = sep.path_start(), xe = sep.path_end();
  const double dy = 2.0 * b / samples, dl = dy / cb;
  const long n_lo = static_cast<long>(std::floor(theta / kTwoPi - (xe + b * tb) / p)) - 1;
  const long n_hi = static_cast<long>(std::ceil(theta / kTwoPi - (xs - b * tb) / p)) + 1;
  out[0] = out[1] = 0.0;
  for (long n = n_lo; n <= n_hi; ++n) {
    const double xn = (theta / kTwoPi - static_cast<double>(n)) * p;
    for (int i = 0; i < samples; ++i) {
      const double y = -b + (i + 0.5) * dy;
      const double x = xn - y * tb;
      if (x < xs || x >= xe) continue;
      const double kk = KOfRoll(x - xs) * dl;
      const double sigma = -x * sb + y * cb;
      const double e = sep.Separation(x, y, n, theta);
      out[0] += kk * e;
      out[1] += kk * sigma * e;
    }
  }
}

/// Relative L2 error of a representation against pointwise values (max over the channels).
double RelativeL2(const std::vector<VectorX>& exact, const std::vector<double>& thetas,
                  const geardyn::Coefficient& c) {
  const int channels = static_cast<int>(exact.front().size());
  VectorX mean = VectorX::Zero(channels), approx(channels);
  for (const VectorX& v : exact) mean += v / static_cast<double>(exact.size());
  VectorX err2 = VectorX::Zero(channels), var2 = VectorX::Zero(channels);
  for (size_t i = 0; i < exact.size(); ++i) {
    geardyn::Evaluate(c, thetas[i], approx);
    err2 += (exact[i] - approx).cwiseAbs2();
    var2 += (exact[i] - mean).cwiseAbs2();
  }
  double worst = 0.0;
  for (int ch = 0; ch < channels; ++ch) worst = std::max(worst, std::sqrt(err2[ch] / var2[ch]));
  return worst;
}

}  // namespace

int main() {
  std::printf(
      "# wp_transmission_error: helical eps_alpha = 1.55, eps_beta = 1.30, z = 25/61 (P = 1525),"
      " tip reliefs, crowning, slope, pitch errors, runout\n");
  std::printf("method,knob,wall_time_s,error,evaluations\n");
  geardyn::ZoneOfAction zone;
  zone.length = kEps * kPitch;
  zone.face_width = kFace;
  zone.transverse_base_pitch = kPitch;
  zone.base_helix_angle = std::atan(1.3 * kPitch / kFace);
  zone.pitch_point_offset = 0.2 * kPitch;
  const double g = kEps * kPitch;
  const geardyn::StiffnessProfile tooth = geardyn::StiffnessProfile::PiecewiseLinear(
      {0.0, 0.3 * g, 0.7 * g, g}, {0.6 * kK, kK, kK, 0.5 * kK});
  geardyn::ToothModifications m;
  m.pinion_tip_relief = {12 * kUm, 0.35 * kPitch, geardyn::ReliefShape::kLinear};
  m.gear_tip_relief = {9 * kUm, 0.45 * kPitch, geardyn::ReliefShape::kParabolic};
  m.lead_crowning = 5 * kUm;
  m.lead_slope = -7 * kUm;
  std::mt19937 rng(2024);
  geardyn::ToothErrors err;
  err.pinion_teeth = 25;
  err.gear_teeth = 61;
  err.pinion_pitch_deviations = ClosedPitch(25, &rng);
  err.gear_pitch_deviations = ClosedPitch(61, &rng);
  err.pinion_runout = 10 * kUm;
  err.pinion_runout_phase = 0.4;
  err.gear_runout = 15 * kUm;
  err.gear_runout_phase = -1.1;
  const TransmissionErrorModel model(geardyn::ContactLineModel(zone, tooth), m, err);
  const auto period = static_cast<int>(model.period_meshes());
  const double span = kTwoPi * period;
  const double b = 0.5 * kFace;
  const double kbar = geardyn::MakeFourierMeshCoefficient(model.contact_lines(), 0).mean()[0];
  const double es = 10 * kUm;

  // --- 1. pointwise: exact split Gauss–Legendre vs sampled quadrature on 512 phases.
  const int grid = 512;
  std::vector<VectorX> exact(grid, VectorX(2));
  std::vector<double> grid_theta(grid);
  for (int i = 0; i < grid; ++i) {
    grid_theta[i] = (i + 0.5) * span / grid;
    model.CalcChannels(grid_theta[i], exact[i]);
  }
  {
    VectorX out(2);
    double sink = 0.0;
    const double t = TimeIt([&] {
      for (int i = 0; i < grid; ++i) {
        model.CalcChannels(grid_theta[i], out);
        sink += out[0];
      }
    });
    Row("exact", 0, t, 0.0, grid);
    if (!std::isfinite(sink)) return 1;
  }
  const int lines = static_cast<int>(std::ceil(kEps + 1.3)) + 3;
  for (int samples : {8, 32, 128, 512, 2048, 8192}) {
    double out[2];
    double worst = 0.0;
    for (int i = 0; i < grid; ++i) {
      Sampled(model, grid_theta[i], samples, out);
      worst = std::max(worst, std::abs(out[0] - exact[i][0]) / (kbar * es));
      worst = std::max(worst, std::abs(out[1] - exact[i][1]) / (kbar * es * b));
    }
    double sink = 0.0;
    const double t = TimeIt([&] {
      for (int i = 0; i < grid; ++i) {
        Sampled(model, grid_theta[i], samples, out);
        sink += out[0];
      }
    });
    Row("sampled_quadrature", samples, t, worst, 1.0 * grid * samples * lines);
    if (!std::isfinite(sink)) return 1;
  }

  // --- 2. representations over the hunting period (reference: 4096 pointwise phases).
  const int points = 4096;
  std::vector<double> thetas(points);
  std::vector<VectorX> channels(points, VectorX(2)), epsilon(points, VectorX(2));
  for (int i = 0; i < points; ++i) {
    thetas[i] = (i + 0.37) * span / points;
    model.CalcChannels(thetas[i], channels[i]);
    epsilon[i] = model.CalcTransmissionError(thetas[i]);
  }
  const double line_pieces = static_cast<double>(model.LineBreakpoints().size() - 1);
  for (int h : {1, 2, 4, 8, 16, 32}) {
    const int terms = h * period;
    const double t = TimeIt([&] { (void)geardyn::MakeSeparationFourierCoefficient(model, terms); });
    const geardyn::Coefficient f = geardyn::MakeSeparationFourierCoefficient(model, terms);
    Row("channels_fourier_exact", h, t, RelativeL2(channels, thetas, f), line_pieces * 6);
  }
  for (int spm : {4, 8, 16, 32, 64, 128}) {
    const double t = TimeIt([&] { (void)geardyn::MakeSeparationTableCoefficient(model, spm); });
    const geardyn::Coefficient tab = geardyn::MakeSeparationTableCoefficient(model, spm);
    Row("channels_table_linear", spm, t, RelativeL2(channels, thetas, tab), 1.0 * spm * period);
  }
  for (int spm : {4, 8, 16, 32, 64, 128}) {
    const double t =
        TimeIt([&] { (void)geardyn::MakeTransmissionErrorTableCoefficient(model, spm); });
    const geardyn::Coefficient tab = geardyn::MakeTransmissionErrorTableCoefficient(model, spm);
    Row("epsilon_table_linear", spm, t, RelativeL2(epsilon, thetas, tab), 1.0 * spm * period);
  }
  for (int h : {1, 2, 4, 8, 16, 32}) {
    const double t = TimeIt(
        [&] { (void)geardyn::MakeTransmissionErrorFourierCoefficient(model, h * period, 4 * h); });
    const geardyn::Coefficient f =
        geardyn::MakeTransmissionErrorFourierCoefficient(model, h * period, 4 * h);
    Row("epsilon_fourier_fft", h, t, RelativeL2(epsilon, thetas, f), 4.0 * h * period);
  }
  return 0;
}
