#include "geardyn/quasi_static.hpp"

#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <string>

#include "geardyn/analyses/time_response.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/system/probes.hpp"

namespace geardyn::app {
namespace {

// Relative difference of K and STE one mesh cycle apart accepted as "identical teeth" [-]: the
// static solves converge to round-off, so anything above 1e-6 is a real tooth-to-tooth change.
constexpr double kCyclePeriodicityTol = 1e-6;

// The mesh force pair and its 2×2 tangent at the static state.
struct PairTangent {
  Vector2 force = Vector2::Zero();      // F = [F_η [N], M_ζ [N·m]]
  Matrix2 stiffness = Matrix2::Zero();  // ∂F/∂δ [N/m, N, N·m]
};

// Nonlinear core: condense the internal coordinates, project on δ = G q_pair (see the @file).
PairTangent NonlinearTangent(const SystemMesh& mesh, const NonlinearMeshCore& core,
                             double mesh_theta, const VectorX& state, int num_dofs,
                             int internal_offset) {
  const int n = core.num_coordinates();
  const int ni = core.num_internal_coordinates();
  VectorX x = VectorX::Zero(n);
  for (int c = 0; c < 12; ++c) {
    if (mesh.dofs[c] >= 0) x(c) = state(mesh.dofs[c]);
  }
  x.tail(ni) = state.segment(num_dofs + internal_offset, ni);
  const auto ws = core.MakeWorkspace();
  NonlinearMeshCoreOutput out = core.MakeOutput();
  core.CalcForces(*ws, mesh_theta, 0.0, x, VectorX::Zero(n), true, &out);
  // out.stiffness = −∂force/∂x; condensed on the 12 body coordinates (internal ones in
  // equilibrium): K12 = S_bb − S_bi S_ii⁻¹ S_ib.
  MatrixX k12 = out.stiffness.topLeftCorner(12, 12);
  if (ni > 0) {
    const Eigen::FullPivLU<MatrixX> lu(out.stiffness.bottomRightCorner(ni, ni));
    k12 -= out.stiffness.topRightCorner(12, ni) * lu.solve(out.stiffness.bottomLeftCorner(ni, 12));
  }
  // A = (G Gᵀ)⁺ G: the pair of the body forces f12 = −Gᵀ F, F = −A f12; K2 = A K12 Aᵀ.
  const Eigen::Matrix<double, 12, 2> gt = mesh.G.transpose();
  const Eigen::Matrix<double, 2, 12> a = gt.completeOrthogonalDecomposition().pseudoInverse();
  PairTangent t;
  t.force = -a * out.force.head(12);
  t.stiffness = a * k12 * a.transpose();
  t.stiffness = 0.5 * (t.stiffness + t.stiffness.transpose()).eval();
  return t;
}

}  // namespace

QuasiStaticResult ComputeQuasiStatic(const SystemModel& model,
                                     const std::vector<double>& half_face_widths, int samples) {
  GEARDYN_THROW_UNLESS(samples >= 1 && samples <= kMaxQuasiStaticSamples,
                       "--samples-per-period: the quasi-static samples per mesh cycle must be in "
                       "[1, "
                           << kMaxQuasiStaticSamples << "], got " << samples);
  GEARDYN_THROW_UNLESS(model.num_meshes() > 0, "--quasi-static: the scene has no mesh");
  GEARDYN_CHECK_SIZE(static_cast<int>(half_face_widths.size()), model.num_meshes(),
                     "half_face_widths");
  const auto start = std::chrono::steady_clock::now();
  QuasiStaticResult result;
  ProbeWorkspace probe_ws(model);
  std::vector<int> internal_offset(model.num_meshes(), 0);
  int offset = 0;
  for (int k = 0; k < model.num_meshes(); ++k) {
    const MeshCore& core = model.meshes()[k].core;
    internal_offset[k] = offset;
    if (const auto* p = std::get_if<std::shared_ptr<const NonlinearMeshCore>>(&core)) {
      offset += (*p)->num_internal_coordinates();
    }
  }
  long solves = 0;
  for (int k = 0; k < model.num_meshes(); ++k) {
    const SystemMesh& mesh = model.meshes()[k];
    const bool contact_core =
        std::holds_alternative<std::shared_ptr<const NonlinearMeshCore>>(mesh.core);
    // Linear and slice cores repeat over more than one mesh cycle only through tooth errors. A
    // contact core counts its teeth apart (P = tooth-count period) even when they are identical:
    // checked below by one more static solve one mesh cycle later.
    GEARDYN_THROW_UNLESS(contact_core || PeriodMeshes(mesh.core) == 1,
                         "--quasi-static: mesh "
                             << mesh.name << " repeats over " << PeriodMeshes(mesh.core)
                             << " mesh cycles (tooth errors), but a [mesh.parameters] table holds "
                                "one mesh cycle; drop the tooth errors ([mesh.errors])");
    QuasiStaticMesh out;
    out.parameters.mesh = mesh.name;
    out.parameters.half_face_width = half_face_widths[k];
    for (int s = 0; s < samples; ++s) {
      const double mesh_theta = 2.0 * std::numbers::pi * s / samples;
      const double theta = (mesh_theta - mesh.phase_offset) / mesh.phase_ratio;
      const TimeDomainStatic st = SolveTimeDomainStatic(model, theta);
      ++solves;
      if (!st.summary.ok() && result.summary.ok()) {
        result.summary.status = st.summary.status;
        result.summary.message = "mesh " + mesh.name + ", sample " + std::to_string(s) +
                                 ": static solve: " + st.summary.message;
      }
      for (const std::string& w : st.summary.warnings) {
        if (std::find(result.summary.warnings.begin(), result.summary.warnings.end(), w) ==
            result.summary.warnings.end()) {
          result.summary.warnings.push_back(w);
        }
      }
      const VectorX q = st.state.head(model.num_dofs());
      PairTangent t;
      Vector2 delta = CalcMeshDeflection(model, MeshIndex(k), q);
      std::visit(
          [&](const auto& c) {
            using T = std::decay_t<decltype(c)>;
            if constexpr (std::is_same_v<T, LinearMeshCore>) {
              t.force = EvalMeshProbe(model, probe_ws, MeshIndex(k), theta, q, VectorX()).force;
              t.stiffness = EvalStiffnessCore(c, mesh_theta);
            } else if constexpr (std::is_same_v<T, SliceMeshCore>) {
              SliceMeshWorkspace ws(c);
              const SliceForce f = EvalSliceForce(c, ws, mesh_theta, delta(0), delta(1));
              t.force = f.force;
              t.stiffness = f.jacobian;
            } else {
              t = NonlinearTangent(mesh, *c, mesh_theta, st.state, model.num_dofs(),
                                   internal_offset[k]);
            }
          },
          mesh.core);
      // ε = δ − K2⁺ F: the LTV mesh's static deflection ε + K2⁻¹F is then δ.
      const Vector2 eps = delta - t.stiffness.completeOrthogonalDecomposition().solve(t.force);
      MeshParameterSamples& p = out.parameters;
      p.stiffness.push_back(std::max(0.0, t.stiffness(0, 0)));
      p.stiffness_h.push_back(-t.stiffness(0, 1));
      p.stiffness_mu_b2.push_back(t.stiffness(1, 1));
      p.transmission_error.push_back(eps(0));
      out.loaded_ste.push_back(delta(0));
      out.force.push_back(t.force(0));
    }
    if (contact_core && PeriodMeshes(mesh.core) > 1 && samples > 0) {
      // The cycle after: the same K and STE at θ + 2π, or the teeth differ.
      const double theta = (2.0 * std::numbers::pi - mesh.phase_offset) / mesh.phase_ratio;
      const TimeDomainStatic st = SolveTimeDomainStatic(model, theta);
      ++solves;
      const VectorX q = st.state.head(model.num_dofs());
      const double ste = CalcMeshDeflection(model, MeshIndex(k), q)(0);
      const PairTangent t =
          NonlinearTangent(mesh, *std::get<std::shared_ptr<const NonlinearMeshCore>>(mesh.core),
                           2.0 * std::numbers::pi, st.state, model.num_dofs(), internal_offset[k]);
      const double k0 = out.parameters.stiffness.front(), ste0 = out.loaded_ste.front();
      GEARDYN_THROW_UNLESS(
          st.summary.ok() && std::abs(t.stiffness(0, 0) - k0) <= kCyclePeriodicityTol * k0 &&
              std::abs(ste - ste0) <= kCyclePeriodicityTol * std::abs(ste0),
          "--quasi-static: mesh " << mesh.name << ": the next mesh cycle differs (K " << k0 << " → "
                                  << t.stiffness(0, 0) << " N/m, STE " << ste0 << " → " << ste
                                  << " m): the teeth are not identical, and a [mesh.parameters] "
                                     "table holds one mesh cycle");
    }
    result.meshes.push_back(std::move(out));
  }
  result.summary.counters["static_solves"] = solves;
  result.summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace geardyn::app
