// Campbell diagram of the speed-dependent mean system (campbell.hpp).
#include "geardyn/analyses/campbell.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numeric>
#include <sstream>
#include <utility>

#include "geardyn/common/check.hpp"
#include "geardyn/common/units.hpp"

namespace geardyn {
namespace {

using ComplexMatrix = Eigen::MatrixXcd;
using ComplexVector = Eigen::VectorXcd;

// One eigenpair kept at a speed.
struct SpeedMode {
  std::complex<double> lambda;
  ComplexVector shape;  // ρ part (mass-weighted, deflated coordinates), unit norm
};

// L⁻¹ X L⁻ᵀ for M = L Lᵀ.
MatrixX MassWeighted(const Eigen::LLT<MatrixX>& llt, const MatrixX& x) {
  const auto l = llt.matrixL();
  const MatrixX y = l.solve(x);
  return l.solve(y.transpose()).transpose();
}

double RelNorm(const MatrixX& a, double scale) { return a.norm() / std::max(scale, 1e-300); }

// The modes of one speed: one eigenvalue per mode (file comment), sorted by frequency, then by
// decreasing growth rate.
std::vector<SpeedMode> SolveSpeed(const MatrixX& k, const MatrixX& k2, const MatrixX& c,
                                  const MatrixX& g, double s, double omega_s) {
  const Eigen::Index m = k.rows();
  MatrixX a = MatrixX::Zero(2 * m, 2 * m);
  a.topRightCorner(m, m) = omega_s * MatrixX::Identity(m, m);
  a.bottomLeftCorner(m, m) = -(k + s * s * k2) / omega_s;
  a.bottomRightCorner(m, m) = -(c + s * g);
  const Eigen::EigenSolver<MatrixX> solver(a, true);
  GEARDYN_DEMAND(solver.info() == Eigen::Success);
  const ComplexVector& values = solver.eigenvalues();
  const ComplexMatrix vectors = solver.eigenvectors();
  const double im_tol = 1e-6 * omega_s;
  std::vector<Eigen::Index> complex_ones;
  std::vector<Eigen::Index> real_ones;
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    if (values[i].imag() > im_tol) {
      complex_ones.push_back(i);
    } else if (std::abs(values[i].imag()) <= im_tol) {
      real_ones.push_back(i);
    }
  }
  std::sort(real_ones.begin(), real_ones.end(),
            [&](Eigen::Index x, Eigen::Index y) { return values[x].real() > values[y].real(); });
  std::vector<SpeedMode> modes;
  const auto keep = [&](Eigen::Index i, bool real) {
    SpeedMode mode;
    mode.lambda = real ? std::complex<double>(values[i].real(), 0.0) : values[i];
    mode.shape = vectors.col(i).head(m);
    const double norm = mode.shape.norm();
    if (norm > 0.0) mode.shape /= norm;
    modes.push_back(std::move(mode));
  };
  for (Eigen::Index i : complex_ones) {
    if (static_cast<Eigen::Index>(modes.size()) < m) keep(i, false);
  }
  for (Eigen::Index i : real_ones) {
    if (static_cast<Eigen::Index>(modes.size()) < m) keep(i, true);
  }
  std::sort(modes.begin(), modes.end(), [](const SpeedMode& x, const SpeedMode& y) {
    if (x.lambda.imag() != y.lambda.imag()) return x.lambda.imag() < y.lambda.imag();
    return x.lambda.real() > y.lambda.real();
  });
  return modes;
}

// Clusters of (near-)repeated frequencies of one speed's modes (sorted by frequency).
std::vector<std::vector<int>> Clusters(const std::vector<SpeedMode>& modes, double rel_tol) {
  std::vector<std::vector<int>> clusters;
  for (int i = 0; i < static_cast<int>(modes.size()); ++i) {
    const double f = modes[static_cast<std::size_t>(i)].lambda.imag();
    if (!clusters.empty()) {
      const double f0 = modes[static_cast<std::size_t>(clusters.back().back())].lambda.imag();
      if (std::abs(f - f0) <= rel_tol * std::max(std::abs(f), std::abs(f0))) {
        clusters.back().push_back(i);
        continue;
      }
    }
    clusters.push_back({i});
  }
  return clusters;
}

// assignment[mode of `next`] = mode index of `prev` it continues, with its MAC (file comment).
std::vector<std::pair<int, double>> MatchModes(const std::vector<SpeedMode>& prev,
                                               const std::vector<SpeedMode>& next,
                                               double cluster_rel_tol) {
  const std::vector<std::vector<int>> clusters = Clusters(prev, cluster_rel_tol);
  std::vector<ComplexMatrix> bases;
  for (const std::vector<int>& cluster : clusters) {
    ComplexMatrix span(prev.front().shape.size(), static_cast<Eigen::Index>(cluster.size()));
    for (std::size_t k = 0; k < cluster.size(); ++k) {
      span.col(static_cast<Eigen::Index>(k)) = prev[static_cast<std::size_t>(cluster[k])].shape;
    }
    const Eigen::HouseholderQR<ComplexMatrix> qr(span);
    bases.push_back(
        qr.householderQ() *
        ComplexMatrix::Identity(span.rows(), static_cast<Eigen::Index>(cluster.size())));
  }
  struct Score {
    double mac;
    int mode;
    int cluster;
  };
  std::vector<Score> scores;
  for (int j = 0; j < static_cast<int>(next.size()); ++j) {
    for (int c = 0; c < static_cast<int>(clusters.size()); ++c) {
      const double mac =
          (bases[static_cast<std::size_t>(c)].adjoint() * next[static_cast<std::size_t>(j)].shape)
              .squaredNorm();
      scores.push_back({std::min(mac, 1.0), j, c});
    }
  }
  std::stable_sort(scores.begin(), scores.end(),
                   [](const Score& a, const Score& b) { return a.mac > b.mac; });
  std::vector<int> cluster_of(next.size(), -1);
  std::vector<double> mac_of(next.size(), 0.0);
  std::vector<int> capacity;
  for (const auto& cluster : clusters) capacity.push_back(static_cast<int>(cluster.size()));
  for (const Score& score : scores) {
    const auto j = static_cast<std::size_t>(score.mode);
    const auto c = static_cast<std::size_t>(score.cluster);
    if (cluster_of[j] >= 0 || capacity[c] == 0) continue;
    cluster_of[j] = score.cluster;
    mac_of[j] = score.mac;
    --capacity[c];
  }
  std::vector<std::pair<int, double>> assignment(next.size(), {-1, 0.0});
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    std::vector<int> members;  // next modes in this cluster, already in frequency order
    for (std::size_t j = 0; j < next.size(); ++j) {
      if (cluster_of[j] == static_cast<int>(c)) members.push_back(static_cast<int>(j));
    }
    for (std::size_t k = 0; k < members.size(); ++k) {
      assignment[static_cast<std::size_t>(members[k])] = {
          clusters[c][k], mac_of[static_cast<std::size_t>(members[k])]};
    }
  }
  return assignment;
}

ModeType DominantKind(const std::array<double, kNumDofKinds>& e) {
  const auto kind = static_cast<DofKind>(std::max_element(e.begin(), e.end()) - e.begin());
  switch (kind) {
    case DofKind::kRotationAxial:
      return ModeType::kRotational;
    case DofKind::kTranslationTransverse:
      return ModeType::kTranslational;
    case DofKind::kTranslationAxial:
      return ModeType::kAxial;
    case DofKind::kRotationTilt:
      return ModeType::kRocking;
  }
  return ModeType::kRotational;
}

// Relative kinetic energy below which a member set counts as at rest in a complex mode (the
// eigenvectors of the non-symmetric state matrix carry more round-off than the symmetric solver's;
// 1e-6 is an amplitude ratio of 1e-3).
constexpr double kComplexModeRestTol = 1e-6;

struct ModeLabels {
  ModeType type = ModeType::kRotational;
  PlanetaryModeType planetary = PlanetaryModeType::kMixed;
};

ModeLabels LabelMode(const ComplexVector& q, const MatrixX& mass, const DofMap& dofs,
                     bool planetary, bool zero) {
  const ComplexVector mq = mass * q;
  std::array<double, kNumDofKinds> by_kind{};
  double central_axial = 0.0;    // θz, z of sun, ring, carrier
  double central_lateral = 0.0;  // x, y, θx, θy of sun, ring, carrier
  double total = 0.0;
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    const double e = std::abs((std::conj(q[i]) * mq[i]).real());
    total += e;
    const int i_dof = static_cast<int>(i);
    by_kind[static_cast<std::size_t>(dofs.dof_kind(i_dof))] += e;
    const BodyRole role = dofs.body_role(dofs.dof_body(i_dof));
    if (role == BodyRole::kSun || role == BodyRole::kRing || role == BodyRole::kCarrier) {
      const DofKind kind = dofs.dof_kind(i_dof);
      if (kind == DofKind::kRotationAxial || kind == DofKind::kTranslationAxial) {
        central_axial += e;
      } else {
        central_lateral += e;
      }
    }
  }
  ModeLabels labels;
  labels.type = zero ? ModeType::kRigidBody : DominantKind(by_kind);
  if (planetary) {
    const double tol = kComplexModeRestTol * std::max(total, 1e-300);
    if (central_axial + central_lateral <= tol) {
      labels.planetary = PlanetaryModeType::kPlanet;
    } else if (central_lateral <= tol) {
      labels.planetary = PlanetaryModeType::kRotational;
    } else if (central_axial <= tol) {
      labels.planetary = PlanetaryModeType::kTranslational;
    }
  }
  return labels;
}

}  // namespace

bool CampbellOptions::IsValid(std::string* why) const {
  std::ostringstream out;
  if (speeds.empty()) {
    out << "speeds: need at least one speed";
  } else if (!(zero_tol > 0.0 && zero_tol < 1.0)) {
    out << "zero_tol: must be in (0, 1), got " << zero_tol;
  } else if (!(cluster_rel_tol >= 0.0 && cluster_rel_tol < 0.1)) {
    out << "cluster_rel_tol: must be in [0, 0.1), got " << cluster_rel_tol;
  } else if (!(mac_warning > 0.0 && mac_warning < 1.0)) {
    out << "mac_warning: must be in (0, 1), got " << mac_warning;
  } else if (!(instability_tol > 0.0 && instability_tol < 1e-2)) {
    out << "instability_tol: must be in (0, 1e-2), got " << instability_tol;
  } else {
    for (std::size_t i = 0; i < speeds.size(); ++i) {
      if (!std::isfinite(speeds[i]) || speeds[i] < 0.0) {
        out << "speeds[" << i << "]: must be finite and ≥ 0, got " << speeds[i];
        break;
      }
      if (i > 0 && !(speeds[i] > speeds[i - 1])) {
        out << "speeds: must be strictly increasing, got " << speeds[i - 1] << " then "
            << speeds[i];
        break;
      }
    }
  }
  if (why != nullptr) *why = out.str();
  return out.str().empty();
}

CampbellResult ComputeCampbell(const CampbellProblem& problem, const CampbellOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  std::string why;
  GEARDYN_THROW_UNLESS(options.IsValid(&why), why);
  const Eigen::Index n = problem.mass.rows();
  GEARDYN_THROW_UNLESS(n > 0, "ComputeCampbell: the model has no DOFs");
  for (const MatrixX* x : {&problem.mass, &problem.damping, &problem.stiffness, &problem.gyroscopic,
                           &problem.speed_stiffness}) {
    GEARDYN_THROW_UNLESS(x->rows() == n && x->cols() == n,
                         "ComputeCampbell: every matrix must be " << n << " × " << n);
  }
  GEARDYN_THROW_UNLESS(problem.dofs.num_dofs() == n, "ComputeCampbell: DOF map size mismatch");
  for (const CampbellExcitation& e : problem.excitations) {
    GEARDYN_THROW_UNLESS(std::isfinite(e.hz_per_speed) && e.hz_per_speed > 0.0,
                         "excitation '" << e.name << "': hz_per_speed must be > 0");
  }

  CampbellResult result;
  result.speeds = options.speeds;
  const Eigen::LLT<MatrixX> llt(problem.mass);
  if (llt.info() != Eigen::Success) {
    result.summary.status = Status::kNumericalIssue;
    result.summary.message = "the mass matrix is not positive definite (Cholesky failed)";
    return result;
  }
  const MatrixX k_t = MassWeighted(llt, problem.stiffness);
  const MatrixX c_t = MassWeighted(llt, problem.damping);
  const MatrixX g_t = MassWeighted(llt, problem.gyroscopic);
  const MatrixX k2_t = MassWeighted(llt, problem.speed_stiffness);
  const Eigen::SelfAdjointEigenSolver<MatrixX> base(0.5 * (k_t + k_t.transpose()));
  const VectorX& lambda = base.eigenvalues();
  const double lambda_max = std::max(lambda.cwiseAbs().maxCoeff(), 1e-300);
  if (lambda.minCoeff() < -options.zero_tol * lambda_max) {
    result.summary.warnings.push_back(
        "K̄ has a negative eigenvalue (" + std::to_string(lambda.minCoeff()) +
        " rad²/s²): the mean system is statically unstable at zero speed");
  }
  std::vector<Eigen::Index> rigid;
  std::vector<Eigen::Index> elastic;
  for (Eigen::Index i = 0; i < lambda.size(); ++i) {
    (std::abs(lambda[i]) <= options.zero_tol * lambda_max ? rigid : elastic).push_back(i);
  }
  MatrixX v_r(n, static_cast<Eigen::Index>(rigid.size()));
  MatrixX v_e(n, static_cast<Eigen::Index>(elastic.size()));
  for (std::size_t k = 0; k < rigid.size(); ++k) {
    v_r.col(static_cast<Eigen::Index>(k)) = base.eigenvectors().col(rigid[k]);
  }
  for (std::size_t k = 0; k < elastic.size(); ++k) {
    v_e.col(static_cast<Eigen::Index>(k)) = base.eigenvectors().col(elastic[k]);
  }
  result.num_rigid_body_modes = static_cast<int>(rigid.size());
  MatrixX basis = MatrixX::Identity(n, n);
  MatrixX coriolis_coupling;  // V_eᵀ G̃₁ V_r when deflated (Routh reduction, file comment)
  if (!rigid.empty() && !elastic.empty()) {
    constexpr double kCouplingTol = 1e-9;
    // V_eᵀK̃₂V_r is not required to vanish: it is the O(s²) change of the rigid mode's shape
    // (file comment), dropped with an O(s⁴) effect on the elastic frequencies.
    const bool invariant = RelNorm(v_r.transpose() * k2_t * v_r, k2_t.norm()) <= kCouplingTol &&
                           RelNorm(v_r.transpose() * g_t * v_r, g_t.norm()) <= kCouplingTol &&
                           RelNorm(c_t * v_r, c_t.norm()) <= kCouplingTol;
    if (invariant) {
      basis = v_e;
      coriolis_coupling = v_e.transpose() * g_t * v_r;
      result.deflated = true;
    } else {
      result.summary.warnings.push_back(
          "the rigid-body modes are not free of speed stiffness energy or damping (e.g. "
          "mass-proportional damping): not deflated, so their zero eigenvalues stay in the problem "
          "and "
          "their growth rates are round-off");
    }
  }
  const MatrixX k_r = basis.transpose() * k_t * basis;
  MatrixX k2_r = basis.transpose() * k2_t * basis;
  if (result.deflated) k2_r += coriolis_coupling * coriolis_coupling.transpose();
  const MatrixX c_r = basis.transpose() * c_t * basis;
  const MatrixX g_r = basis.transpose() * g_t * basis;
  const Eigen::Index m = basis.cols();
  const double omega_s = std::sqrt(lambda_max);
  const bool planetary = problem.dofs.num_planets() > 0;

  // Static critical speeds: K_ρ + s² K_2ρ singular (file comment).
  {
    const Eigen::SelfAdjointEigenSolver<MatrixX> kr(0.5 * (k_r + k_r.transpose()));
    if (kr.eigenvalues().minCoeff() > 0.0) {
      const MatrixX w = kr.operatorInverseSqrt();
      const Eigen::SelfAdjointEigenSolver<MatrixX> mu(w * (0.5 * (k2_r + k2_r.transpose())) * w,
                                                      Eigen::EigenvaluesOnly);
      const double mu_scale = std::max(mu.eigenvalues().cwiseAbs().maxCoeff(), 1e-300);
      for (Eigen::Index i = 0; i < mu.eigenvalues().size(); ++i) {
        const double value = mu.eigenvalues()[i];
        if (value < -1e-12 * mu_scale)
          result.static_critical_speeds.push_back(std::sqrt(-1.0 / value));
      }
      std::sort(result.static_critical_speeds.begin(), result.static_critical_speeds.end());
    }
  }

  const auto num_speeds = options.speeds.size();
  result.tracks.resize(static_cast<std::size_t>(m));
  for (CampbellTrack& t : result.tracks) {
    t.frequency_hz.assign(num_speeds, 0.0);
    t.growth_rate.assign(num_speeds, 0.0);
    t.mac.assign(num_speeds, 1.0);
    t.labels.assign(num_speeds, ModeType::kRotational);
    if (planetary) t.planetary_labels.assign(num_speeds, PlanetaryModeType::kMixed);
    t.unstable.assign(num_speeds, 0);
  }
  const MatrixX to_q = llt.matrixU().solve(basis);  // q = L⁻ᵀ V ρ
  std::vector<SpeedMode> prev;
  std::vector<int> track_of_prev;  // track of each mode of `prev`
  int low_mac_matches = 0;
  double lowest_mac = 1.0;
  for (std::size_t si = 0; si < num_speeds; ++si) {
    const double s = options.speeds[si];
    std::vector<SpeedMode> modes = SolveSpeed(k_r, k2_r, c_r, g_r, s, omega_s);
    GEARDYN_DEMAND(static_cast<Eigen::Index>(modes.size()) == m);
    std::vector<int> track_of(modes.size());
    std::vector<double> mac(modes.size(), 1.0);
    if (si == 0) {
      std::iota(track_of.begin(), track_of.end(), 0);
    } else {
      const auto assignment = MatchModes(prev, modes, options.cluster_rel_tol);
      for (std::size_t j = 0; j < modes.size(); ++j) {
        track_of[j] = track_of_prev[static_cast<std::size_t>(assignment[j].first)];
        mac[j] = assignment[j].second;
        if (mac[j] < options.mac_warning) {
          ++low_mac_matches;
          lowest_mac = std::min(lowest_mac, mac[j]);
        }
      }
    }
    for (std::size_t j = 0; j < modes.size(); ++j) {
      CampbellTrack& t = result.tracks[static_cast<std::size_t>(track_of[j])];
      const std::complex<double> l = modes[j].lambda;
      t.frequency_hz[si] = std::max(l.imag(), 0.0) / (2.0 * kPi);
      t.growth_rate[si] = l.real();
      t.mac[si] = mac[j];
      t.unstable[si] = l.real() > options.instability_tol * omega_s ? 1 : 0;
      const ComplexVector q = to_q.cast<std::complex<double>>() * modes[j].shape;
      const ModeLabels labels =
          LabelMode(q, problem.mass, problem.dofs, planetary, std::abs(l) <= 1e-9 * omega_s);
      t.labels[si] = labels.type;
      if (planetary) t.planetary_labels[si] = labels.planetary;
    }
    prev = std::move(modes);
    track_of_prev = std::move(track_of);
  }
  if (low_mac_matches > 0) {
    std::ostringstream w;
    w << low_mac_matches << " track continuation(s) had MAC < " << options.mac_warning
      << " (lowest " << lowest_mac
      << "): near crossings or veerings of similar shapes the track order is uncertain; refine "
         "the speed grid there";
    result.summary.warnings.push_back(w.str());
  }

  // Instabilities: runs of consecutive grid speeds with an unstable mode of one kind (the tracks
  // of a merged flutter pair swap between speeds, so the runs are not per track).
  for (const char* kind : {"divergence", "flutter"}) {
    const bool flutter = std::string(kind) == "flutter";
    const auto unstable_at = [&](std::size_t si, std::size_t ti) {
      const CampbellTrack& t = result.tracks[ti];
      return t.unstable[si] != 0 && (t.frequency_hz[si] > 0.0) == flutter;
    };
    for (std::size_t si = 0; si < num_speeds;) {
      bool any = false;
      for (std::size_t ti = 0; ti < result.tracks.size() && !any; ++ti) any = unstable_at(si, ti);
      if (!any) {
        ++si;
        continue;
      }
      CampbellInstability run;
      run.kind = kind;
      run.speed_begin = options.speeds[si];
      std::size_t end = si;
      for (; end < num_speeds; ++end) {
        bool here = false;
        for (std::size_t ti = 0; ti < result.tracks.size(); ++ti) {
          if (!unstable_at(end, ti)) continue;
          here = true;
          if (std::find(run.tracks.begin(), run.tracks.end(), static_cast<int>(ti)) ==
              run.tracks.end()) {
            run.tracks.push_back(static_cast<int>(ti));
          }
          run.max_growth_rate = std::max(run.max_growth_rate, result.tracks[ti].growth_rate[end]);
        }
        if (!here) break;
      }
      run.speed_end = options.speeds[end - 1];
      std::sort(run.tracks.begin(), run.tracks.end());
      result.instabilities.push_back(run);
      si = end;
    }
  }
  std::sort(result.instabilities.begin(), result.instabilities.end(),
            [](const CampbellInstability& x, const CampbellInstability& y) {
              return x.speed_begin < y.speed_begin;
            });
  // Crossings with the excitation lines.
  for (std::size_t ti = 0; ti < result.tracks.size(); ++ti) {
    const CampbellTrack& t = result.tracks[ti];
    for (std::size_t ei = 0; ei < problem.excitations.size(); ++ei) {
      const double h = problem.excitations[ei].hz_per_speed;
      for (std::size_t si = 0; si + 1 < num_speeds; ++si) {
        const double f0 = t.frequency_hz[si];
        const double f1 = t.frequency_hz[si + 1];
        if (f0 <= 0.0 || f1 <= 0.0) continue;
        const double s0 = options.speeds[si];
        const double s1 = options.speeds[si + 1];
        const double d0 = f0 - h * s0;
        const double d1 = f1 - h * s1;
        if (d0 == 0.0 && s0 > 0.0) {
          result.crossings.push_back({static_cast<int>(ti), static_cast<int>(ei), s0, f0});
        } else if ((d0 > 0.0) != (d1 > 0.0) && d1 != 0.0) {
          const double u = d0 / (d0 - d1);
          const double speed = s0 + u * (s1 - s0);
          result.crossings.push_back(
              {static_cast<int>(ti), static_cast<int>(ei), speed, h * speed});
        }
      }
    }
  }
  std::sort(result.crossings.begin(), result.crossings.end(),
            [](const CampbellCrossing& a, const CampbellCrossing& b) { return a.speed < b.speed; });

  result.summary.counters["speeds"] = static_cast<long>(num_speeds);
  result.summary.counters["modes"] = static_cast<long>(m);
  result.summary.counters["state_dofs"] = static_cast<long>(2 * m);
  result.summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace geardyn
