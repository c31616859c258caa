// Linear harmonic balance with sparse harmonics (harmonic_balance.hpp "Long hunting periods"): a
// transmission error given as a mesh-periodic coefficient plus a few lines over a long period
// (TransmissionErrorSidebands: a runout), solved without anything indexed up to k_max. Truths:
// * a short hunting period (P = 5): the sparse path equals the dense path on the same model and
//   on the same ε written as one Fourier coefficient over P (the FFT-synthesis path), to
//   round-off — responses, means, RMS, peak-to-peak, amplitudes, element forces;
// * coprime teeth (P = 988 027, ν = c/q = 1/991): the class-0 response equals the response
//   without the runout, and the whole result equals the dense solve of the short equivalent with
//   the same line frequency (P = 991), a different path (dense expansion and sampler over the
//   hunting period, itself checked against GSL time integration in hunting_period_test);
// * the mean-LTI level: the runout class is one harmonic, the closed form
//   (−(cΩ)²M + icΩC + K̄)⁻¹ Gᵀ K̄2 ε_c.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <complex>
#include <functional>
#include <numbers>
#include <optional>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/system/system_harmonics.hpp"
#include "geardyn/system/workspace.hpp"
#include "hb_fixtures.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

using Complex = std::complex<double>;

constexpr double kRoundOff = 1e-9;         // relative: different summation orders, O(H q) terms
constexpr std::int64_t kCoprime = 988027;  // lcm(997, 991)
// A line over the coprime period at ν = 300/991 mesh orders (m = 300·997): fast enough to load
// the mesh (a once-per-revolution runout at ν = 1/991 is absorbed by the pair's free rotation,
// giving a DTE ~1e-9 of the mesh-order one), and with the short equivalent m = 300 over 991.
constexpr std::int64_t kLine = 300 * 997;

// Lines of ε_η over P_s: c_i at harmonics m_i.
TransmissionErrorSidebands Lines(std::int64_t period, std::vector<std::int64_t> m,
                                 std::vector<Complex> c) {
  TransmissionErrorSidebands sb;
  sb.period_meshes = period;
  sb.harmonics = std::move(m);
  sb.coefficients = MatrixXc::Zero(2, static_cast<Eigen::Index>(c.size()));
  for (size_t i = 0; i < c.size(); ++i) sb.coefficients(0, static_cast<Eigen::Index>(i)) = c[i];
  return sb;
}

LinearMeshCore Core(std::optional<Coefficient> eps, TransmissionErrorSidebands sb = {}) {
  const test::HandPairParams p;
  return LinearMeshCore(MeshCoreLevel::kBlankenshipSingh, test::SmoothStiffness(p.k, 0.25, 0.1),
                        p.b, std::move(eps), MeshDamping::FromRatio(0.05), false, std::move(sb));
}

// Mesh-periodic ε: ε_η = 1e-6 cos θ + 0.3e-6 sin 2θ + 0.1e-6 cos 3θ.
FourierCoefficient MeshPeriodicError() {
  return test::SmoothTransmissionError(1e-6, 0.3e-6, 0.1e-6);
}

double Rel(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-300); }

// Column of Q_k in a result (dense: by k; sparse: by its position in kept_harmonics).
VectorXc Response(const HbResult& r, int k) {
  if (!r.sparse_harmonics) return r.response_harmonics.col(k);
  const auto it = std::lower_bound(r.kept_harmonics.begin(), r.kept_harmonics.end(), k);
  EXPECT_TRUE(it != r.kept_harmonics.end() && *it == k) << k;
  return r.response_harmonics.col(it - r.kept_harmonics.begin());
}
double Amplitude(const HbResult& r, const HbMeshOutput& m, int k) {
  if (!r.sparse_harmonics) return m.dte_amplitudes(k);
  const auto it = std::lower_bound(r.kept_harmonics.begin(), r.kept_harmonics.end(), k);
  return m.dte_amplitudes(it - r.kept_harmonics.begin());
}

// Every output of `b` equals `a` within tol; harmonics compared through the map k_a → k_b.
void ExpectSameResult(const HbResult& a, const HbResult& b, double tol,
                      const std::function<int(int)>& to_b, bool peak_to_peak = true) {
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  const double scale = a.response_harmonics.norm();
  for (int k : a.kept_harmonics) {
    EXPECT_LE((Response(a, k) - Response(b, to_b(k))).norm(), tol * scale) << "k = " << k;
  }
  for (size_t m = 0; m < a.meshes.size(); ++m) {
    const HbMeshOutput& x = a.meshes[m];
    const HbMeshOutput& y = b.meshes[m];
    EXPECT_LE(Rel(y.mean_dte, x.mean_dte), tol);
    EXPECT_LE(Rel(y.rms_dte, x.rms_dte), tol);
    EXPECT_LE(Rel(y.mean_force, x.mean_force), tol);
    EXPECT_LE(Rel(y.rms_force, x.rms_force), tol);
    if (peak_to_peak) {
      EXPECT_LE(Rel(y.peak_to_peak_dte, x.peak_to_peak_dte), tol);
      EXPECT_LE(Rel(y.peak_to_peak_force, x.peak_to_peak_force), tol);
    }
    for (int k : a.kept_harmonics) {
      EXPECT_NEAR(Amplitude(b, y, to_b(k)), Amplitude(a, x, k), tol * x.rms_dte) << k;
    }
  }
  ASSERT_EQ(a.elements.size(), b.elements.size());
  for (size_t e = 0; e < a.elements.size(); ++e) {
    const double fs = a.elements[e].rms_force.norm() + a.elements[e].mean_force.norm();
    EXPECT_LE((a.elements[e].mean_force - b.elements[e].mean_force).norm(), tol * fs);
    EXPECT_LE((a.elements[e].rms_force - b.elements[e].rms_force).norm(), tol * fs);
  }
}

TEST(HbSparseHarmonicsTest, ShortHuntingPeriodSparseEqualsDense) {
  // P = 5: the runout line m = 1 (3 µm) and m = 2, on the mesh-periodic ε and an LTV stiffness.
  const auto sb = Lines(5, {1, 2}, {Complex(1.5e-6, 0.0), Complex(0.0, 0.2e-6)});
  const SystemModel model = test::LoadedPair(Core(MeshPeriodicError(), sb), 200.0, 0.02);
  ASSERT_EQ(model.period_meshes(), 5);
  // The same ε as one Fourier coefficient over 5 meshes (the pre-existing dense form).
  const FourierCoefficient mesh = MeshPeriodicError();
  MatrixXc h = MatrixXc::Zero(2, 15);
  for (int j = 1; j <= 3; ++j) h.col(5 * j - 1) = mesh.harmonics().col(j - 1);
  h.col(0) += sb.coefficients.col(0);
  h.col(1) += sb.coefficients.col(1);
  const SystemModel fourier =
      test::LoadedPair(Core(FourierCoefficient(mesh.mean(), h, 5)), 200.0, 0.02);

  HbOptions options;
  options.harmonics = 8;
  options.time_samples = 5 * 256;  // 256 per mesh: the sparse sampler's per-period samples
  options.keep_harmonics = true;
  for (const double f_m : {900.0, 2600.0}) {
    options.harmonic_storage = HbHarmonicStorage::kDense;
    const HbResult dense = SolveHarmonicBalance(model, options, f_m);
    const HbResult dense_fourier = SolveHarmonicBalance(fourier, options, f_m);
    options.harmonic_storage = HbHarmonicStorage::kSparse;
    const HbResult sparse = SolveHarmonicBalance(model, options, f_m);
    ASSERT_TRUE(dense.summary.ok() && sparse.summary.ok() && dense_fourier.summary.ok());
    EXPECT_FALSE(dense.sparse_harmonics);
    EXPECT_TRUE(sparse.sparse_harmonics);
    EXPECT_EQ(sparse.kept_harmonics, dense.kept_harmonics);
    EXPECT_EQ(sparse.summary.counters.at("forcing_classes"), 3);  // 0, 1, 2
    const auto same = [](int k) { return k; };
    ExpectSameResult(dense, sparse, kRoundOff, same);
    ExpectSameResult(dense_fourier, sparse, kRoundOff, same);
    // The runout line is there (not a trivial agreement on zero).
    EXPECT_GT(Amplitude(sparse, sparse.meshes[0], 1), 1e-3 * sparse.meshes[0].rms_dte);
  }
}

TEST(HbSparseHarmonicsTest, CoprimeRunoutClassZeroEqualsTheResponseWithoutRunout) {
  // 997/991 teeth: one line over the hunting period of 988 027 meshes.
  const auto sb = Lines(kCoprime, {kLine}, {Complex(2.5e-6, 1e-6)});
  const SystemModel with = test::LoadedPair(Core(MeshPeriodicError(), sb), 200.0, 0.02);
  const SystemModel without = test::LoadedPair(Core(MeshPeriodicError()), 200.0, 0.02);
  HbOptions options;
  options.harmonics = 8;
  options.keep_harmonics = true;
  const HbResult a = SolveHarmonicBalance(with, options, 2600.0);  // kAuto: sparse
  const HbResult b = SolveHarmonicBalance(without, options, 2600.0);
  ASSERT_TRUE(a.summary.ok()) << a.summary.BriefReport();
  ASSERT_TRUE(b.summary.ok());
  EXPECT_TRUE(a.sparse_harmonics);
  EXPECT_EQ(a.period_meshes, kCoprime);
  EXPECT_EQ(a.summary.counters.at("forcing_classes"), 2);
  EXPECT_EQ(a.kept_harmonics.size(), 9u + 17u);  // j q (j ≤ 8), j q ± 299 100
  const double scale = b.response_harmonics.norm();
  for (int j = 0; j <= 8; ++j) {
    EXPECT_LE((Response(a, j * static_cast<int>(kCoprime)) - b.response_harmonics.col(j)).norm(),
              kRoundOff * scale)
        << "mesh order " << j;
  }
  EXPECT_LE(Rel(a.meshes[0].mean_dte, b.meshes[0].mean_dte), kRoundOff);
  // Parseval over orthogonal classes: RMS² with = RMS² without + the runout class's.
  double runout2 = 0.0;
  for (size_t i = 0; i < a.kept_harmonics.size(); ++i) {
    if (a.kept_harmonics[i] % kCoprime != 0) {
      runout2 += 0.5 * std::pow(a.meshes[0].dte_amplitudes(static_cast<Eigen::Index>(i)), 2);
    }
  }
  EXPECT_LE(Rel(std::pow(a.meshes[0].rms_dte, 2), std::pow(b.meshes[0].rms_dte, 2) + runout2),
            kRoundOff);
  EXPECT_GT(runout2, 1e-4 * std::pow(b.meshes[0].rms_dte, 2));
}

TEST(HbSparseHarmonicsTest, CoprimeRunoutEqualsTheDenseShortEquivalent) {
  // The class of the line ν = 299 100/988 027 = 300/991 solves the same equations as a line
  // m = 300 over P = 991 (frequencies (j ± ν) ω_m), which the dense path solves over its whole
  // hunting period.
  const Complex c(2.5e-6, 1e-6);
  const SystemModel coprime =
      test::LoadedPair(Core(MeshPeriodicError(), Lines(kCoprime, {kLine}, {c})), 200.0, 0.02);
  const SystemModel short_period =
      test::LoadedPair(Core(MeshPeriodicError(), Lines(991, {300}, {c})), 200.0, 0.02);
  HbOptions options;
  options.harmonics = 8;
  options.keep_harmonics = true;
  for (const double f_m : {1300.0, 3100.0}) {
    options.time_samples = 0;
    const HbResult a = SolveHarmonicBalance(coprime, options, f_m);
    options.time_samples = 991 * 256;  // the sparse sampler's 256 per mesh
    options.harmonic_storage = HbHarmonicStorage::kDense;
    const HbResult b = SolveHarmonicBalance(short_period, options, f_m);
    options.harmonic_storage = HbHarmonicStorage::kAuto;
    ASSERT_TRUE(a.summary.ok() && b.summary.ok());
    ASSERT_TRUE(a.sparse_harmonics);
    ASSERT_FALSE(b.sparse_harmonics);
    const auto to_coprime = [](int k) {  // j·991 + d ↔ j·988 027 + 997 d, d ∈ {0, ±300}
      const int j = (k + 495) / 991;
      return j * static_cast<int>(kCoprime) + (k - j * 991) * 997;
    };
    ExpectSameResult(b, a, kRoundOff, to_coprime, /*peak_to_peak=*/false);
    // The sparse peak-to-peak is sampled over 4096 of 988 027 periods: a lower bound of the
    // dense one over every period, and close to it (the window meets most of the 991 phases).
    EXPECT_GT(Amplitude(a, a.meshes[0], kLine), 0.01 * a.meshes[0].rms_dte);  // not trivial
    for (size_t m = 0; m < a.meshes.size(); ++m) {
      EXPECT_LE(a.meshes[m].peak_to_peak_dte, b.meshes[m].peak_to_peak_dte * (1.0 + kRoundOff));
      EXPECT_GE(a.meshes[m].peak_to_peak_dte, b.meshes[m].peak_to_peak_dte * (1.0 - 1e-3));
      EXPECT_LE(a.meshes[m].peak_to_peak_force, b.meshes[m].peak_to_peak_force * (1.0 + kRoundOff));
      EXPECT_GE(a.meshes[m].peak_to_peak_force, b.meshes[m].peak_to_peak_force * (1.0 - 1e-3));
    }
  }
}

TEST(HbSparseHarmonicsTest, MeanLtiRunoutClassIsTheClosedFormHarmonicResponse) {
  const Complex c(2.5e-6, -1e-6);
  const LinearMeshCore core =
      MakeMeanLinearMeshCore(Core(std::nullopt, Lines(kCoprime, {997}, {c})));
  const SystemModel model = test::LoadedPair(core, 0.0, 0.02);
  HbOptions options;
  options.harmonics = 4;
  options.keep_harmonics = true;
  const double f_m = 2200.0;
  const HbResult hb = SolveHarmonicBalance(model, options, f_m);
  ASSERT_TRUE(hb.summary.ok()) << hb.summary.BriefReport();
  ASSERT_TRUE(hb.sparse_harmonics);
  // Q_c = (−(cΩ)² M + i cΩ C + K̄)⁻¹ Gᵀ K̄2 ε_c, Ω = ω_m/P, c = 997.
  const double w = 997.0 * 2.0 * std::numbers::pi * f_m / static_cast<double>(kCoprime);
  SystemWorkspace ws(model);
  const MatrixX K = AssembleStiffness(model, ws, 0.0);
  const MatrixX C = AssembleDamping(model, ws, 0.0);
  const MatrixXc A = (K - w * w * model.DenseMass()).cast<Complex>() + Complex(0.0, w) * C;
  const SystemMesh& mesh = model.meshes()[0];
  const Vector2c load = EvalStiffnessCore(core, 0.0).cast<Complex>() * Vector2c(c, 0.0);
  VectorXc f = VectorXc::Zero(model.num_dofs());
  for (int a = 0; a < 12; ++a) {
    if (mesh.dofs[a] >= 0) f(mesh.dofs[a]) += mesh.G.col(a).cast<Complex>().dot(load);
  }
  const VectorXc expected = A.partialPivLu().solve(f);
  EXPECT_LE((Response(hb, 997) - expected).norm(), kRoundOff * expected.norm());
  // Nothing else is forced: the DTE is that one line, RMS = |DTE_c| √2.
  Complex dte = -c;
  for (int a = 0; a < 12; ++a) {
    if (mesh.dofs[a] >= 0) dte += mesh.G(0, a) * expected(mesh.dofs[a]);
  }
  EXPECT_LE(Rel(hb.meshes[0].rms_dte, std::sqrt(2.0) * std::abs(dte)), kRoundOff);
  EXPECT_LE(Rel(hb.meshes[0].peak_to_peak_dte, 4.0 * std::abs(dte)), 1e-6);  // sampled window
}

TEST(HbSparseHarmonicsTest, WhatCannotBeSparseIsRefusedWithItsCost) {
  // A long-period ε coefficient (pitch errors) has no sparse form: refused, naming why.
  MatrixXc h = MatrixXc::Zero(2, 40000);
  h(0, 0) = 1e-6;
  const SystemModel model =
      test::LoadedPair(Core(FourierCoefficient(Vector2::Zero(), h, 199999)), 200.0, 0.02);
  HbOptions options;
  options.harmonics = 8;
  options.harmonic_storage = HbHarmonicStorage::kSparse;
  EXPECT_THROWS_MESSAGE(SolveHarmonicBalance(model, options, 2000.0), InvalidInput,
                        "sparse harmonics not possible.*repeats over 199999 mesh cycles");
  options.harmonic_storage = HbHarmonicStorage::kAuto;  // the dense estimate, and why not sparse
  EXPECT_THROWS_MESSAGE(SolveHarmonicBalance(model, options, 2000.0), InvalidInput,
                        "GB.*sparse harmonics.*not possible.*199999");
  // kDirect solves every harmonic up to k_max: not with sparse harmonics.
  const SystemModel coprime = test::LoadedPair(
      Core(MeshPeriodicError(), Lines(kCoprime, {997}, {Complex(1e-6, 0.0)})), 200.0, 0.02);
  options.method = HbMethod::kDirect;
  options.harmonic_storage = HbHarmonicStorage::kAuto;
  EXPECT_THROWS_MESSAGE(SolveHarmonicBalance(coprime, options, 2000.0), InvalidInput,
                        "direct.*not with sparse harmonics");
}

TEST(HbSparseHarmonicsTest, SidebandsOnAStiffnessHarmonicAreRejected) {
  // m/P_s = 5/5 is the mesh order: it belongs in the coefficient.
  EXPECT_THROWS_MESSAGE(Core(std::nullopt, Lines(5, {5}, {Complex(1e-6, 0.0)})), InvalidInput,
                        "sidebands.harmonics\\[0\\].*harmonic of the stiffness period");
  EXPECT_THROWS_MESSAGE(Core(std::nullopt, Lines(5, {0}, {Complex(1e-6, 0.0)})), InvalidInput,
                        "sidebands.harmonics\\[0\\]: must be >= 1");
}

}  // namespace
}  // namespace geardyn
