/// @file
/// @brief SimulateQuasiStatic: the slow roll under load (time_response.hpp) — a static solve at
/// every θ sample and the loaded TE and tangent mesh stiffness of every mesh.
#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>

#include "geardyn/analyses/time_response.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/system/probes.hpp"
#include "td_system.hpp"

namespace geardyn {
namespace {

using internal::TdMeshTerm;

/// The 2×2 tangent ∂F/∂δ of a NonlinearMeshCore: its internal coordinates condensed out of the
/// core's stiffness (K_pp − K_pi K_ii⁻¹ K_ip, 12×12 on the pair), then K2 = G⁺ᵀ K₁₂ G⁺ (exact when
/// the condensed stiffness acts through δ = G q_pair only, as a mesh's must).
Matrix2 CoreTangent(const TdMeshTerm& t, const MatrixX& k) {
  MatrixX k12 = k.topLeftCorner(12, 12);
  if (t.num_internal > 0) {
    const MatrixX kii = k.bottomRightCorner(t.num_internal, t.num_internal);
    const MatrixX kip = k.bottomLeftCorner(t.num_internal, 12);
    const Eigen::LDLT<MatrixX> ldlt(kii);
    if (ldlt.info() == Eigen::Success) k12 -= kip.transpose() * ldlt.solve(kip);
  }
  const Eigen::CompleteOrthogonalDecomposition<MatrixX> cod(MatrixX(t.G.transpose()));
  const MatrixX gp = cod.pseudoInverse();  // (2×12) G⁺ᵀ
  return gp * k12 * gp.transpose();
}

}  // namespace

bool QuasiStaticOptions::IsValid(std::string* why) const {
  std::ostringstream s;
  if (samples_per_mesh < 1 || samples_per_mesh > 65536)
    s << "samples_per_mesh: must be in [1, 65536], got " << samples_per_mesh;
  else if (period_multiple < 1 || period_multiple > 1000)
    s << "period_multiple: must be in [1, 1000], got " << period_multiple;
  else
    return true;
  if (why != nullptr) *why = s.str();
  return false;
}

QuasiStaticResult SimulateQuasiStatic(const SystemModel& model, const QuasiStaticOptions& options,
                                      const TimeProgress& progress,
                                      const std::atomic<bool>* cancel) {
  std::string why;
  if (!options.IsValid(&why)) throw InvalidInput("SimulateQuasiStatic: " + why);
  GEARDYN_THROW_UNLESS(model.num_meshes() > 0, "SimulateQuasiStatic: the model has no meshes");
  const auto start = std::chrono::steady_clock::now();
  const internal::TdSystem sys(model);
  internal::TdWorkspace ws(sys);
  const std::int64_t P = model.period_meshes() * options.period_multiple;
  const std::int64_t total = P * options.samples_per_mesh;
  GEARDYN_THROW_UNLESS(total <= 10000000, "SimulateQuasiStatic: " << total
                                                                  << " θ samples (samples_per_mesh"
                                                                     " × P × period_multiple) "
                                                                     "exceed 1e7");
  const int m = model.num_meshes();
  const auto samples = static_cast<Eigen::Index>(total);
  QuasiStaticResult out;
  out.theta = VectorX::Zero(samples);
  out.meshes.resize(static_cast<std::size_t>(m));
  for (int k = 0; k < m; ++k) {
    QuasiStaticMesh& q = out.meshes[static_cast<std::size_t>(k)];
    q.name = model.meshes()[static_cast<std::size_t>(k)].name;
    q.loaded_te = q.dte = q.force = VectorX::Zero(samples);
    q.stiffness = MatrixX::Zero(3, samples);
  }
  VectorX previous;
  VectorX dte(m);
  Eigen::Index done = 0;
  for (Eigen::Index s = 0; s < samples; ++s) {
    if (cancel != nullptr && cancel->load()) {
      out.summary.status = Status::kNotConverged;
      out.summary.message = "cancelled";
      break;
    }
    const double theta = 2.0 * std::numbers::pi * static_cast<double>(P) * static_cast<double>(s) /
                         static_cast<double>(samples);
    const internal::TdStatic st =
        internal::SolveStatic(sys, ws, theta, previous.size() > 0 ? &previous : nullptr);
    if (!st.ok) {
      out.summary.status = Status::kNotConverged;
      out.summary.message = st.message + " (θ = " + std::to_string(theta) + " rad)";
      break;
    }
    previous = st.x;
    out.theta(s) = theta;
    internal::EvalForces(sys, ws, theta, 0.0, st.x, VectorX::Zero(sys.n), true);
    EvalMeshDte(model, theta, st.x.head(sys.num_dofs), dte);
    for (int k = 0; k < m; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      const TdMeshTerm& t = sys.terms[kk];
      QuasiStaticMesh& q = out.meshes[kk];
      q.loaded_te(s) = CalcMeshDeflection(model, MeshIndex(k), st.x.head(sys.num_dofs))(0);
      q.dte(s) = dte(k);
      q.force(s) = ws.force_eta[kk];
      const Matrix2 j = t.kind == TdMeshTerm::Kind::kNonlinear
                            ? CoreTangent(t, ws.core_out[kk].stiffness)
                            : ws.mesh_tangent[kk];
      q.stiffness(0, s) = j(0, 0);
      q.stiffness(1, s) = -0.5 * (j(0, 1) + j(1, 0));
      q.stiffness(2, s) = j(1, 1);
    }
    done = s + 1;
    if (progress && (s + 1) % 64 == 0) {
      progress(static_cast<double>(s + 1) / static_cast<double>(samples),
               "θ sample " + std::to_string(s + 1));
    }
  }
  if (done < samples) {
    // Keep the samples computed so far.
    out.theta.conservativeResize(done);
    for (QuasiStaticMesh& q : out.meshes) {
      q.loaded_te.conservativeResize(done);
      q.dte.conservativeResize(done);
      q.force.conservativeResize(done);
      q.stiffness.conservativeResize(3, done);
    }
  }
  out.summary.counters["samples"] = static_cast<long>(done);
  out.summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace geardyn
