// Linear harmonic balance on the torus of several mesh frequencies (quasi_periodic_hb.hpp).
//
// The unknowns are, per kept κ, the response Q_κ (n) and the scaled mesh forces λ_{k,κ} (2 per
// mesh; Λ = k_ref λ): the mesh operator enters as P_kᵀ G_kᵀ Λ in the equation of motion and as
// the constraint Λ_κ − Σ_n (K2_n + i w_{κ'} C2_n) G_k P_k Q_{κ'} = −(K2 ε)_κ. Eliminating Λ gives
// the equations of the @file exactly; keeping it costs 2·meshes unknowns per κ but stores 2×12
// instead of 12×12 entries per coupling (6× fewer nonzeros) and the LU's fill runs through them.
#include "geardyn/analyses/quasi_periodic_hb.hpp"

#include <fftw3.h>

#include <Eigen/SparseLU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <iomanip>
#include <mutex>
#include <numbers>
#include <numeric>
#include <sstream>
#include <unordered_map>
#include <variant>

#include "geardyn/common/check.hpp"
#include "geardyn/numerics/fftw_planner.hpp"
#include "geardyn/system/mesh_core.hpp"
#include "geardyn/system/system_harmonics.hpp"
#include "hb_internal.hpp"
#include "system_nhb/system_problem.hpp"
#include "torus_harmonics.hpp"

namespace geardyn {
namespace {

using Complex = std::complex<double>;
using ComplexSparse = internal::ComplexSparse;
using Triplet = Eigen::Triplet<Complex, int>;

constexpr double kMinRcond = 1e-14;  // as the single-frequency HB (hb_solver_impl.hpp)
constexpr double kWarnRcond = 1e-10;
constexpr std::int64_t kMaxTorusPoints = std::int64_t{1} << 22;

std::string FormatG(double x) {
  std::ostringstream s;
  s << std::setprecision(3) << x;
  return s.str();
}

using internal::HarmonicSet;

std::int64_t Binomial(int n, int k) {
  if (k < 0 || k > n) return 0;
  std::int64_t c = 1;
  for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
  return c;
}

// Own-phase unit of mesh k in its base: harmonic n of the mesh is harmonic n·u of the base.
std::int64_t MeshUnit(const QuasiPeriodicBase& base, const SystemMesh& mesh) {
  return base.period_meshes / PeriodMeshes(mesh.core);
}

// Peak-to-peak of Re Σ_κ c_κ e^{iκ·ψ} on an S^d grid (FFTW backward c2c, rank d).
double TorusPeakToPeak(const HarmonicSet& set, int d, int S, const VectorXc& coefficients) {
  std::int64_t points = 1;
  for (int b = 0; b < d; ++b) points *= S;
  std::vector<Complex> grid(static_cast<std::size_t>(points), Complex(0.0, 0.0));
  for (int i = 0; i < set.size(); ++i) {
    std::int64_t idx = 0;
    for (int b = 0; b < d; ++b) {
      const int v = set.order(i)[static_cast<std::size_t>(b)];
      idx = idx * S + ((v % S) + S) % S;
    }
    grid[static_cast<std::size_t>(idx)] += coefficients(i);
  }
  std::vector<int> dims(static_cast<std::size_t>(d), S);
  auto* data = reinterpret_cast<fftw_complex*>(grid.data());
  fftw_plan plan;
  {
    std::lock_guard<std::mutex> lock(FftwPlannerMutex());
    plan = fftw_plan_dft(d, dims.data(), data, data, FFTW_BACKWARD, FFTW_ESTIMATE);
  }
  fftw_execute(plan);
  {
    std::lock_guard<std::mutex> lock(FftwPlannerMutex());
    fftw_destroy_plan(plan);
  }
  double lo = grid.front().real(), hi = lo;
  for (const Complex& z : grid) {
    lo = std::min(lo, z.real());
    hi = std::max(hi, z.real());
  }
  return hi - lo;
}

void CheckModel(const SystemModel& model, std::vector<std::string>* warnings) {
  GEARDYN_THROW_UNLESS(model.num_meshes() > 0,
                       "quasi-periodic harmonic balance: the model has no meshes");
  for (const SystemMesh& mesh : model.meshes()) {
    GEARDYN_THROW_UNLESS(
        !std::holds_alternative<std::shared_ptr<const NonlinearMeshCore>>(mesh.core),
        "quasi-periodic harmonic balance (linear): mesh '"
            << mesh.name << "' has a nonlinear contact core; the linear solver cannot use it");
    GEARDYN_THROW_UNLESS(std::isfinite(mesh.phase_ratio) && mesh.phase_ratio > 0.0,
                         "quasi-periodic harmonic balance: mesh '"
                             << mesh.name << "' has phase ratio " << mesh.phase_ratio
                             << "; it must be finite and > 0");
    if (std::holds_alternative<SliceMeshCore>(mesh.core)) {
      warnings->push_back("mesh '" + mesh.name +
                          "': slice core linearized with every slice loaded (linear harmonic "
                          "balance; contact loss is ignored)");
    }
  }
}

}  // namespace

namespace internal {

void CheckOrderCoversMeshFrequencies(const SystemModel& model,
                                     const std::vector<QuasiPeriodicBase>& bases, int total_order,
                                     const char* field) {
  for (const QuasiPeriodicBase& b : bases) {
    if (b.period_meshes <= total_order) continue;
    std::string names;
    for (int k : b.meshes) {
      const SystemMesh& mesh = model.meshes()[static_cast<std::size_t>(k)];
      if (PeriodMeshes(mesh.core) > 1) names += (names.empty() ? "'" : ", '") + mesh.name + "'";
    }
    GEARDYN_THROW_UNLESS(
        false, field << ": H = " << total_order << " counts harmonics of f_mesh/" << b.period_meshes
                     << " on the base of mesh " << names << " (its tooth errors repeat every "
                     << b.period_meshes << " mesh cycles), so the mesh frequency is order "
                     << b.period_meshes << " and H = " << total_order
                     << " would leave it out; H must be at least " << b.period_meshes
                     << " (or leave the tooth errors out of this analysis)");
  }
}

}  // namespace internal

bool QuasiPeriodicHbOptions::IsValid(std::string* why) const {
  std::ostringstream msg;
  if (total_order < 1 || total_order > kMaxQuasiPeriodicOrder) {
    msg << "QuasiPeriodicHbOptions::total_order: must be in [1, " << kMaxQuasiPeriodicOrder
        << "], got " << total_order;
  } else if (!(std::isfinite(ratio_tolerance) && ratio_tolerance >= 0.0 &&
               ratio_tolerance <= 1e-3)) {
    msg << "QuasiPeriodicHbOptions::ratio_tolerance: must be in [0, 1e-3], got " << ratio_tolerance;
  } else if (samples_per_base < 0 ||
             (samples_per_base > 0 && samples_per_base <= 2 * total_order)) {
    msg << "QuasiPeriodicHbOptions::samples_per_base: must be 0 (automatic) or exceed 2H = "
        << 2 * total_order << " (sampling theorem), got " << samples_per_base;
  } else if (!(std::isfinite(memory_limit_bytes) && memory_limit_bytes >= 1e6 &&
               memory_limit_bytes <= 1e12)) {
    msg << "QuasiPeriodicHbOptions::memory_limit_bytes: must be in [1e6, 1e12], got "
        << memory_limit_bytes;
  }
  if (why != nullptr) *why = msg.str();
  return msg.str().empty();
}

std::vector<QuasiPeriodicBase> FindQuasiPeriodicBases(const SystemModel& model,
                                                      double mesh_frequency_hz,
                                                      const QuasiPeriodicHbOptions& options) {
  std::string why;
  GEARDYN_THROW_UNLESS(options.IsValid(&why), why);
  std::vector<std::string> ignored;
  CheckModel(model, &ignored);
  std::vector<QuasiPeriodicBase> bases;
  for (int k = 0; k < model.num_meshes(); ++k) {
    const SystemMesh& mesh = model.meshes()[static_cast<std::size_t>(k)];
    auto it = std::find_if(bases.begin(), bases.end(), [&](const QuasiPeriodicBase& b) {
      return std::abs(b.phase_ratio - mesh.phase_ratio) <=
             options.ratio_tolerance * std::max(b.phase_ratio, mesh.phase_ratio);
    });
    if (it == bases.end()) {
      bases.push_back({mesh.phase_ratio, 1, 0.0, {}});
      it = bases.end() - 1;
    }
    it->meshes.push_back(k);
    it->period_meshes = std::lcm(it->period_meshes, PeriodMeshes(mesh.core));
  }
  for (QuasiPeriodicBase& b : bases) {
    b.frequency_hz = b.phase_ratio * mesh_frequency_hz / static_cast<double>(b.period_meshes);
  }
  return bases;
}

std::int64_t CountQuasiPeriodicHarmonics(int num_bases, int total_order) {
  // Points of the cross-polytope: Σ_j 2^j C(d, j) C(H, j).
  std::int64_t count = 0;
  for (int j = 0; j <= std::min(num_bases, total_order); ++j) {
    count += (std::int64_t{1} << j) * Binomial(num_bases, j) * Binomial(total_order, j);
  }
  return count;
}

double EstimateQuasiPeriodicHbBytes(const SystemModel& model,
                                    const QuasiPeriodicHbOptions& options) {
  const std::vector<QuasiPeriodicBase> bases = FindQuasiPeriodicBases(model, 1.0, options);
  const int d = static_cast<int>(bases.size());
  const int H = options.total_order;
  const std::int64_t blocks = CountQuasiPeriodicHarmonics(d, H);
  // Matrix nonzeros: the LTI blocks, and per mesh and κ its G entries (twice) plus, per
  // coupling κ' = κ − n u e_b ∈ S, the 2×12 block of (K2 + iwC2) G. The number of κ' along axis b
  // is 2(H − |κ|_1 + |κ_b|) + 1; summed over S by the number of κ with each (|κ|_1 − |κ_b|).
  const double lti =
      static_cast<double>(model.mass().nonZeros() + model.constant_stiffness().nonZeros() +
                          model.constant_damping().nonZeros());
  double couplings = 0.0;  // Σ_κ (2(H − rest) + 1), rest = |κ|_1 − |κ_b|, for one axis
  for (int rest = 0; rest <= H; ++rest) {
    // κ with |other orders|_1 = rest: points of the (d−1)-sphere of radius rest, times the
    // 2(H − rest) + 1 values of κ_b.
    const double shell =
        static_cast<double>(CountQuasiPeriodicHarmonics(d - 1, rest) -
                            (rest > 0 ? CountQuasiPeriodicHarmonics(d - 1, rest - 1) : 0));
    const double along = 2.0 * (H - rest) + 1.0;
    couplings += shell * along * along;
  }
  double mesh = 0.0;
  for (const SystemMesh& m : model.meshes()) {
    int entries = 0;
    for (int r = 0; r < 2; ++r) {
      for (int a = 0; a < 12; ++a) {
        entries += m.dofs[static_cast<std::size_t>(a)] >= 0 && m.G(r, a) != 0.0;
      }
    }
    mesh += static_cast<double>(blocks) * (2.0 + 2.0 * entries) + couplings * entries;
  }
  const double nonzeros = static_cast<double>(blocks) * lti + mesh;
  // LU fill (Eigen's SparseLU, COLAMD, partial pivoting on the equilibrated matrix): measured
  // 5.0, 10.9 and 28.8 × the matrix for 2 bases at H = 4, 8, 16 (41, 145, 545 blocks; the
  // 9-DOF two-mesh test system): ≈ 0.45 blocks^(2/3); 0.5 blocks^(2/3) here.
  const double fill = std::max(1.0, 0.5 * std::pow(static_cast<double>(blocks), 2.0 / 3.0));
  // Complex value + row index ≈ 20 B per nonzero, the matrix and its factors.
  return 20.0 * nonzeros * (1.0 + fill);
}

QuasiPeriodicHbResult SolveQuasiPeriodicHb(const SystemModel& model, double mesh_frequency_hz,
                                           const QuasiPeriodicHbOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  GEARDYN_THROW_UNLESS(std::isfinite(mesh_frequency_hz) && mesh_frequency_hz > 0.0,
                       "quasi-periodic harmonic balance: mesh frequency must be finite and > 0 "
                       "Hz, got "
                           << mesh_frequency_hz);
  QuasiPeriodicHbResult result;
  CheckModel(model, &result.summary.warnings);
  result.bases = FindQuasiPeriodicBases(model, mesh_frequency_hz, options);
  const int d = static_cast<int>(result.bases.size());
  const int H = options.total_order;
  internal::CheckOrderCoversMeshFrequencies(model, result.bases, H,
                                            "QuasiPeriodicHbOptions::total_order");
  const double bytes = EstimateQuasiPeriodicHbBytes(model, options);
  GEARDYN_THROW_UNLESS(bytes <= options.memory_limit_bytes,
                       "QuasiPeriodicHbOptions::total_order: H = "
                           << H << " on " << d << " base frequencies ("
                           << CountQuasiPeriodicHarmonics(d, H) << " harmonics of "
                           << model.num_dofs() << " DOF) would need about " << FormatG(bytes / 1e9)
                           << " GB (limit " << FormatG(options.memory_limit_bytes / 1e9)
                           << " GB); lower the total order");
  int base_of_unit_ratio = -1;
  for (int b = 0; b < d; ++b) {
    if (std::abs(result.bases[static_cast<std::size_t>(b)].phase_ratio - 1.0) <=
        std::max(options.ratio_tolerance, 1e-12)) {
      base_of_unit_ratio = b;
    }
  }
  GEARDYN_THROW_UNLESS(model.harmonic_loads().empty() || base_of_unit_ratio >= 0,
                       "quasi-periodic harmonic balance: the model has harmonic loads at orders of "
                       "the phase of ratio 1, but no mesh runs at ratio 1");
  result.mesh_frequency_hz = mesh_frequency_hz;
  result.total_order = H;

  const int n = model.num_dofs();
  const int num_meshes = model.num_meshes();
  const HarmonicSet set(d, H);
  const int N = set.size();
  const int block = n + 2 * num_meshes;  // unknowns per κ: Q_κ, then λ_{k,κ} per mesh
  std::vector<int> base_of(static_cast<std::size_t>(num_meshes), 0);
  for (int b = 0; b < d; ++b) {
    for (int k : result.bases[static_cast<std::size_t>(b)].meshes) {
      base_of[static_cast<std::size_t>(k)] = b;
    }
  }
  std::vector<double> omega(static_cast<std::size_t>(d));  // Ω_b [rad/s]
  for (int b = 0; b < d; ++b) {
    omega[static_cast<std::size_t>(b)] =
        2.0 * std::numbers::pi * result.bases[static_cast<std::size_t>(b)].frequency_hz;
  }
  VectorX w(N);  // w_κ [rad/s]
  result.orders.resize(d, N);
  for (int i = 0; i < N; ++i) {
    w(i) = 0.0;
    for (int b = 0; b < d; ++b) {
      const int v = set.order(i)[static_cast<std::size_t>(b)];
      result.orders(b, i) = v;
      w(i) += v * omega[static_cast<std::size_t>(b)];
    }
  }

  // Mesh harmonics in each mesh's own phase, up to the largest difference 2H of base orders.
  std::vector<SparseMeshHarmonics> own(static_cast<std::size_t>(num_meshes));
  std::vector<std::int64_t> unit(static_cast<std::size_t>(num_meshes));
  double k_ref = 0.0;
  MatrixX mean_stiffness = model.DenseConstantStiffness();
  for (int k = 0; k < num_meshes; ++k) {
    const SystemMesh& mesh = model.meshes()[static_cast<std::size_t>(k)];
    unit[static_cast<std::size_t>(k)] = MeshUnit(
        result.bases[static_cast<std::size_t>(base_of[static_cast<std::size_t>(k)])], mesh);
    const int harmonics = static_cast<int>(2 * H / unit[static_cast<std::size_t>(k)]);
    own[static_cast<std::size_t>(k)] = ExpandOwnPhaseMeshHarmonics(mesh, harmonics);
    const Matrix2 k0 = own[static_cast<std::size_t>(k)].stiffness[0].real();
    k_ref = std::max(k_ref, std::abs(k0(0, 0)));
    const Eigen::Matrix<double, 12, 12> kb = mesh.G.transpose() * k0 * mesh.G;
    for (int a = 0; a < 12; ++a) {
      for (int c = 0; c < 12; ++c) {
        const int da = mesh.dofs[static_cast<std::size_t>(a)];
        const int dc = mesh.dofs[static_cast<std::size_t>(c)];
        if (da >= 0 && dc >= 0) mean_stiffness(da, dc) += kb(a, c);
      }
    }
  }
  if (!(k_ref > 0.0)) k_ref = 1.0;
  const internal::RigidModes rigid = internal::ComputeRigidModes(mean_stiffness);

  // ---- Assembly.
  std::vector<Triplet> triplets;
  const SparseMatrix& M = model.mass();
  const SparseMatrix& C0 = model.constant_damping();
  SparseMatrix K0 = model.constant_stiffness();
  SparseMatrix penalty;
  if (rigid.count() > 0) {
    const double umax = rigid.U.cwiseAbs().maxCoeff();
    const SparseMatrix U = rigid.U.sparseView(1e-14 * umax, 1.0);
    penalty = U * SparseMatrix(U.transpose());
  }
  triplets.reserve(static_cast<std::size_t>(N) *
                   static_cast<std::size_t>(M.nonZeros() + K0.nonZeros() + C0.nonZeros() +
                                            num_meshes * (26 + 24 * (2 * H + 1))));
  const auto add_sparse = [&](const SparseMatrix& A, int i, Complex factor) {
    for (int c = 0; c < A.outerSize(); ++c) {
      for (SparseMatrix::InnerIterator it(A, c); it; ++it) {
        triplets.emplace_back(i * block + static_cast<int>(it.row()),
                              i * block + static_cast<int>(it.col()), factor * it.value());
      }
    }
  };
  for (int i = 0; i < N; ++i) {
    add_sparse(M, i, Complex(-w(i) * w(i), 0.0));
    add_sparse(C0, i, Complex(0.0, w(i)));
    add_sparse(K0, i, Complex(1.0, 0.0));
  }
  const int zero = set.Find(std::vector<int>(static_cast<std::size_t>(d), 0));
  if (rigid.count() > 0) add_sparse(penalty, zero, Complex(1.0, 0.0));
  VectorXc rhs = VectorXc::Zero(static_cast<Eigen::Index>(N) * block);
  // External loads: f0 (balanced against the rigid-body modes) and the harmonic loads.
  VectorXc f0 = model.constant_load().cast<Complex>();
  const double unbalanced = internal::BalanceMeanLoad(rigid, &f0);
  rhs.segment(static_cast<Eigen::Index>(zero) * block, n) += f0;
  for (const SystemHarmonicLoad& h : model.harmonic_loads()) {
    const QuasiPeriodicBase& base = result.bases[static_cast<std::size_t>(base_of_unit_ratio)];
    const std::int64_t m = static_cast<std::int64_t>(h.order) * base.period_meshes;
    if (m > H) continue;
    for (int sign : {1, -1}) {
      std::vector<int> k(static_cast<std::size_t>(d), 0);
      k[static_cast<std::size_t>(base_of_unit_ratio)] = static_cast<int>(sign * m);
      const int i = set.Find(k);
      for (int a = 0; a < kBodyDofs; ++a) {
        if (h.dofs[static_cast<std::size_t>(a)] < 0) continue;
        const Complex f = 0.5 * (sign > 0 ? h.amplitude(a) : std::conj(h.amplitude(a)));
        rhs(static_cast<Eigen::Index>(i) * block + h.dofs[static_cast<std::size_t>(a)]) += f;
      }
    }
  }
  // Meshes: P_kᵀ G_kᵀ k_ref λ in the equation of motion; the constraint rows
  // λ_κ − Σ_n (K2_n + i w_{κ'} C2_n)/k_ref G Q_{κ'} = −(K2 ε)_κ / k_ref.
  for (int k = 0; k < num_meshes; ++k) {
    const SystemMesh& mesh = model.meshes()[static_cast<std::size_t>(k)];
    const SparseMeshHarmonics& h = own[static_cast<std::size_t>(k)];
    const int b = base_of[static_cast<std::size_t>(k)];
    const std::int64_t u = unit[static_cast<std::size_t>(k)];
    const int nmax = static_cast<int>(h.stiffness.size()) - 1;
    for (int i = 0; i < N; ++i) {
      const int row_lambda = i * block + n + 2 * k;
      for (int r = 0; r < 2; ++r) {
        triplets.emplace_back(row_lambda + r, row_lambda + r, Complex(1.0, 0.0));
        for (int a = 0; a < 12; ++a) {
          const int da = mesh.dofs[static_cast<std::size_t>(a)];
          if (da >= 0 && mesh.G(r, a) != 0.0) {
            triplets.emplace_back(i * block + da, row_lambda + r, Complex(k_ref * mesh.G(r, a)));
          }
        }
      }
      std::vector<int> kappa = set.order(i);
      const int own_order = kappa[static_cast<std::size_t>(b)];
      for (int nn = -nmax; nn <= nmax; ++nn) {
        kappa[static_cast<std::size_t>(b)] = own_order - static_cast<int>(nn * u);
        const int j = set.Find(kappa);
        if (j < 0) continue;
        const std::size_t an = static_cast<std::size_t>(std::abs(nn));
        const Matrix2c ks = nn >= 0 ? h.stiffness[an] : Matrix2c(h.stiffness[an].conjugate());
        const Matrix2c cs = nn >= 0 ? h.damping[an] : Matrix2c(h.damping[an].conjugate());
        const Matrix2c T = (ks + Complex(0.0, w(j)) * cs) / k_ref;
        const Eigen::Matrix<Complex, 2, 12> TG = T * mesh.G.cast<Complex>();
        for (int r = 0; r < 2; ++r) {
          for (int a = 0; a < 12; ++a) {
            const int da = mesh.dofs[static_cast<std::size_t>(a)];
            if (da >= 0 && TG(r, a) != Complex(0.0, 0.0)) {
              triplets.emplace_back(row_lambda + r, j * block + da, -TG(r, a));
            }
          }
        }
      }
      kappa[static_cast<std::size_t>(b)] = own_order;
      // Load at κ = n u e_b (κ's other orders zero).
      bool on_axis = own_order % u == 0;
      for (int c = 0; c < d && on_axis; ++c)
        on_axis = c == b || kappa[static_cast<std::size_t>(c)] == 0;
      if (on_axis && std::abs(own_order / u) <= nmax) {
        const int nn = static_cast<int>(own_order / u);
        const std::size_t an = static_cast<std::size_t>(std::abs(nn));
        const Vector2c load = nn >= 0 ? h.load[an] : Vector2c(h.load[an].conjugate());
        rhs.segment<2>(row_lambda) -= load / k_ref;
      }
    }
  }
  ComplexSparse A(static_cast<Eigen::Index>(N) * block, static_cast<Eigen::Index>(N) * block);
  A.setFromTriplets(triplets.begin(), triplets.end());
  triplets.clear();
  triplets.shrink_to_fit();
  A.makeCompressed();
  result.summary.counters["unknowns"] = static_cast<long>(A.rows());
  result.summary.counters["harmonics"] = N;
  result.summary.counters["bases"] = d;
  result.summary.counters["matrix_nonzeros"] = static_cast<long>(A.nonZeros());
  result.summary.counters["rigid_body_modes"] = rigid.count();
  if (unbalanced > 1e-8) {
    result.summary.warnings.push_back(
        "the constant load has a part along the rigid-body modes (relative " + FormatG(unbalanced) +
        "); removed (the supports cannot react it)");
  }

  // ---- Solve. Rows, then columns, scaled to unit max-norm (one Ruiz pass): the DOFs mix
  // metres, radians and the scaled mesh forces, and the condition number of the scaled matrix
  // is the one that says how many digits the solve loses.
  VectorX row_scale = VectorX::Zero(A.rows()), col_scale = VectorX::Zero(A.cols());
  for (Eigen::Index c = 0; c < A.outerSize(); ++c) {
    for (ComplexSparse::InnerIterator it(A, c); it; ++it) {
      row_scale(it.row()) = std::max(row_scale(it.row()), std::abs(it.value()));
    }
  }
  for (Eigen::Index i = 0; i < A.rows(); ++i)
    row_scale(i) = row_scale(i) > 0.0 ? 1.0 / row_scale(i) : 1.0;
  for (Eigen::Index c = 0; c < A.outerSize(); ++c) {
    for (ComplexSparse::InnerIterator it(A, c); it; ++it) {
      it.valueRef() *= row_scale(it.row());
      col_scale(c) = std::max(col_scale(c), std::abs(it.value()));
    }
  }
  for (Eigen::Index c = 0; c < A.outerSize(); ++c) {
    col_scale(c) = col_scale(c) > 0.0 ? 1.0 / col_scale(c) : 1.0;
    for (ComplexSparse::InnerIterator it(A, c); it; ++it) it.valueRef() *= col_scale(c);
  }
  rhs = rhs.cwiseProduct(row_scale.cast<Complex>());
  Eigen::SparseLU<ComplexSparse> lu;
  lu.analyzePattern(A);
  lu.factorize(A);
  const auto finish = [&]() {
    result.summary.wall_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return result;
  };
  if (lu.info() != Eigen::Success) {
    result.summary.status = Status::kNumericalIssue;
    result.summary.message = "quasi-periodic harmonic balance: the factorization failed at " +
                             FormatG(mesh_frequency_hz) +
                             " Hz (singular operator: an undamped resonance?)";
    return finish();
  }
  result.summary.counters["lu_nonzeros"] = static_cast<long>(lu.nnzL() + lu.nnzU());
  const VectorXc x = VectorXc(lu.solve(rhs)).cwiseProduct(col_scale.cast<Complex>());
  const double rcond = internal::EstimateSparseRcond(A, lu);
  result.reciprocal_condition = rcond;
  if (!x.allFinite() || rcond < kMinRcond) {
    result.summary.status = Status::kNumericalIssue;
    result.summary.message =
        "quasi-periodic harmonic balance: the operator is singular to working precision "
        "(estimated 1/cond " +
        FormatG(rcond) + ") at " + FormatG(mesh_frequency_hz) + " Hz: an undamped resonance?";
    return finish();
  }
  if (rcond < kWarnRcond) {
    result.summary.warnings.push_back("ill-conditioned operator (estimated 1/cond " +
                                      FormatG(rcond) + "): expect to lose about " +
                                      FormatG(std::round(-std::log10(rcond))) + " digits");
  }
  result.harmonics.resize(n, N);
  for (int i = 0; i < N; ++i) {
    result.harmonics.col(i) = x.segment(static_cast<Eigen::Index>(i) * block, n);
  }

  // ---- Outputs.
  int S = options.samples_per_base;
  if (S == 0) {
    S = 16;
    while (S < 4 * H + 4) S *= 2;
    const auto points = [&](int s) {
      std::int64_t p = 1;
      for (int b = 0; b < d; ++b) p *= s;
      return p;
    };
    while (S / 2 > 2 * H && points(S) > kMaxTorusPoints) S /= 2;
  }
  std::int64_t grid_points = 1;
  for (int b = 0; b < d; ++b) grid_points *= S;
  const bool sample_torus = grid_points <= 4 * kMaxTorusPoints;
  result.samples_per_base = sample_torus ? S : 0;
  if (!sample_torus) {
    result.summary.warnings.push_back(
        "the torus grid of " + std::to_string(d) + " bases would exceed " +
        std::to_string(4 * kMaxTorusPoints) +
        " points: peak-to-peak DTE is the upper bound Σ of the line amplitudes");
  }
  double max_rms = 0.0, tail_sq = 0.0;
  const int tail_order = (3 * H) / 4;
  for (int k = 0; k < num_meshes; ++k) {
    const SystemMesh& mesh = model.meshes()[static_cast<std::size_t>(k)];
    const SparseMeshHarmonics& h = own[static_cast<std::size_t>(k)];
    const int b = base_of[static_cast<std::size_t>(k)];
    const std::int64_t u = unit[static_cast<std::size_t>(k)];
    VectorXc D =
        result.harmonics.transpose() * internal::ScatteredMeshRow(mesh, 0, n).cast<Complex>();
    for (int i = 0; i < N; ++i) {
      const std::vector<int>& kappa = set.order(i);
      bool on_axis = kappa[static_cast<std::size_t>(b)] % u == 0;
      for (int c = 0; c < d && on_axis; ++c)
        on_axis = c == b || kappa[static_cast<std::size_t>(c)] == 0;
      const std::int64_t nn = kappa[static_cast<std::size_t>(b)] / u;
      if (!on_axis || std::abs(nn) >= static_cast<std::int64_t>(h.transmission_error.size())) {
        continue;
      }
      const Vector2c& e = h.transmission_error[static_cast<std::size_t>(std::abs(nn))];
      D(i) -= nn >= 0 ? e(0) : std::conj(e(0));
    }
    QuasiPeriodicMeshOutput out;
    out.name = mesh.name;
    out.base = b;
    out.mean_dte = D(zero).real();
    double sq = 0.0, tail = 0.0, sum_amplitudes = 0.0;
    for (int i = 0; i < N; ++i) {
      if (i == zero) continue;
      sq += std::norm(D(i));
      int norm = 0;
      for (int v : set.order(i)) norm += std::abs(v);
      if (norm > tail_order) tail += std::norm(D(i));
      sum_amplitudes += std::abs(D(i));
    }
    out.rms_dte = std::sqrt(sq);
    max_rms = std::max(max_rms, out.rms_dte);
    tail_sq = std::max(tail_sq, tail);
    out.peak_to_peak_dte = sample_torus ? TorusPeakToPeak(set, d, S, D) : 2.0 * sum_amplitudes;
    VectorXc F(N);  // F_η,κ = k_ref λ_η,κ [N]
    for (int i = 0; i < N; ++i) F(i) = k_ref * x(static_cast<Eigen::Index>(i) * block + n + 2 * k);
    out.mean_force = F(zero).real();
    double force_sq = 0.0, force_sum = 0.0;
    for (int i = 0; i < N; ++i) {
      if (i == zero) continue;
      force_sq += std::norm(F(i));
      force_sum += std::abs(F(i));
    }
    out.rms_force = std::sqrt(force_sq);
    out.peak_to_peak_force = sample_torus ? TorusPeakToPeak(set, d, S, F) : 2.0 * force_sum;
    double largest = 0.0;
    for (int i = 0; i < N; ++i) {
      if (i != zero) largest = std::max(largest, std::abs(D(i)));
    }
    for (int i = 0; i < N; ++i) {
      if (i == zero || w(i) < 0.0 || (w(i) == 0.0 && i < zero)) continue;
      if (std::abs(D(i)) <= 1e-12 * largest) continue;
      out.lines.push_back({set.order(i), w(i) / (2.0 * std::numbers::pi), 2.0 * std::abs(D(i))});
    }
    std::sort(out.lines.begin(), out.lines.end(),
              [](const QuasiPeriodicLine& x, const QuasiPeriodicLine& y) {
                return x.amplitude > y.amplitude;
              });
    result.meshes.push_back(std::move(out));
  }
  result.summary.error_estimate = max_rms > 0.0 ? std::sqrt(tail_sq) / max_rms : 0.0;
  return finish();
}

}  // namespace geardyn
