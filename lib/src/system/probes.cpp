// Output probes (geardyn/system/probes.hpp): DTE, torsional TE, mesh force pair, element forces
// and the linear probe operator y = P q − o(θ).
#include "geardyn/system/probes.hpp"

#include <cmath>
#include <memory>
#include <type_traits>
#include <variant>

#include "geardyn/common/check.hpp"
#include "geardyn/common/overloaded.hpp"

namespace geardyn {
namespace {

// Pair coordinates of the rotations about the gear axes (θz of body i and body j).
constexpr int kThetaZi = 5;
constexpr int kThetaZj = 11;

void CheckMesh(const SystemModel& model, MeshIndex k, const char* what) {
  GEARDYN_THROW_UNLESS(
      k.value() >= 0 && k.value() < model.num_meshes(),
      what << ": mesh index " << k.value() << " out of range [0, " << model.num_meshes() << ")");
}

void CheckState(const SystemModel& model, const Eigen::Ref<const VectorX>& q,
                const Eigen::Ref<const VectorX>& qdot, const char* what) {
  GEARDYN_THROW_UNLESS(
      q.size() == model.num_dofs(),
      what << ": q must have num_dofs = " << model.num_dofs() << " entries, got " << q.size());
  GEARDYN_THROW_UNLESS(qdot.size() == 0 || qdot.size() == model.num_dofs(),
                       what << ": qdot must be empty or have num_dofs = " << model.num_dofs()
                            << " entries, got " << qdot.size());
}

Vector12 Gather(const SystemMesh& mesh, const Eigen::Ref<const VectorX>& x) {
  Vector12 out = Vector12::Zero();
  for (int a = 0; a < 12; ++a) {
    if (mesh.dofs[a] >= 0) out(a) = x(mesh.dofs[a]);
  }
  return out;
}

// ε_η of a mesh at the system phase θ (0 for cores without an ε pair).
Vector2 TransmissionError(const SystemMesh& mesh, double theta) {
  if (const auto* core = std::get_if<LinearMeshCore>(&mesh.core)) {
    return EvalTransmissionError(*core, mesh.MeshPhase(theta));
  }
  return Vector2::Zero();
}

bool HasTransmissionError(const SystemMesh& mesh) {
  const auto* core = std::get_if<LinearMeshCore>(&mesh.core);
  return core != nullptr && core->has_transmission_error();
}

}  // namespace

ProbeWorkspace::ProbeWorkspace(const SystemModel& model) : model_id(model.id()) {
  const std::vector<SystemMesh>& meshes = model.meshes();
  slice_workspace_of_mesh.assign(meshes.size(), -1);
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    if (const auto* slice = std::get_if<SliceMeshCore>(&meshes[k].core)) {
      slice_workspace_of_mesh[k] = static_cast<int>(slice_workspaces.size());
      slice_workspaces.emplace_back(*slice);
    }
  }
}

bool ProbeWorkspace::IsCompatibleWith(const SystemModel& model) const {
  return model_id == model.id();
}

Vector2 CalcMeshDeflection(const SystemModel& model, MeshIndex k,
                           const Eigen::Ref<const VectorX>& q) {
  CheckMesh(model, k, "CalcMeshDeflection");
  CheckState(model, q, VectorX(), "CalcMeshDeflection");
  const SystemMesh& mesh = model.meshes()[static_cast<std::size_t>(k.value())];
  return mesh.G * Gather(mesh, q);
}

MeshProbeValues EvalMeshProbe(const SystemModel& model, ProbeWorkspace& ws, MeshIndex k,
                              double theta, const Eigen::Ref<const VectorX>& q,
                              const Eigen::Ref<const VectorX>& qdot) {
  CheckMesh(model, k, "EvalMeshProbe");
  CheckState(model, q, qdot, "EvalMeshProbe");
  GEARDYN_THROW_UNLESS(std::isfinite(theta), "EvalMeshProbe: theta must be finite, got " << theta);
  GEARDYN_THROW_UNLESS(ws.IsCompatibleWith(model),
                       "EvalMeshProbe: workspace was built for another model");
  const SystemMesh& mesh = model.meshes()[static_cast<std::size_t>(k.value())];
  const double phase = mesh.MeshPhase(theta);
  const Vector12 qk = Gather(mesh, q);
  const Vector2 rate = qdot.size() > 0 ? Vector2(mesh.G * Gather(mesh, qdot)) : Vector2::Zero();

  MeshProbeValues v;
  v.deflection = mesh.G * qk;
  v.transmission_error = TransmissionError(mesh, theta);
  v.dte = v.deflection(0) - v.transmission_error(0);
  v.torsional_te = mesh.G(0, kThetaZi) * qk(kThetaZi) + mesh.G(0, kThetaZj) * qk(kThetaZj) -
                   v.transmission_error(0);
  std::visit(Overloaded{
                 [&](const LinearMeshCore& core) {
                   // F = K2 (δ − ε) + C2 δ̇ (spec 01 §3; B–S Eq. 39).
                   v.force = EvalStiffnessCore(core, phase) * (v.deflection - v.transmission_error);
                   if (qdot.size() > 0) {
                     v.force += EvalDampingCore(core, phase, mesh.damping_coefficient) * rate;
                   }
                 },
                 [&](const SliceMeshCore& core) {
                   SliceMeshWorkspace& sws =
                       ws.slice_workspaces[static_cast<std::size_t>(ws.slice_workspace_of_mesh[k])];
                   const SliceForce f =
                       EvalSliceForce(core, sws, phase, v.deflection(0), v.deflection(1));
                   v.force = f.force;
                   if (qdot.size() > 0)
                     v.force += CalcSliceDampingCore(f, mesh.damping_coefficient) * rate;
                 },
                 [&](const std::shared_ptr<const NonlinearMeshCore>&) {
                   v.has_force = false;  // its force acts on its own coordinates, not on δ
                 },
             },
             mesh.core);
  return v;
}

void EvalMeshDte(const SystemModel& model, double theta, const Eigen::Ref<const VectorX>& q,
                 Eigen::Ref<VectorX> dte) {
  CheckState(model, q, VectorX(), "EvalMeshDte");
  GEARDYN_THROW_UNLESS(std::isfinite(theta), "EvalMeshDte: theta must be finite, got " << theta);
  GEARDYN_CHECK_SIZE(dte.size(), model.num_meshes(), "EvalMeshDte: dte");
  const std::vector<SystemMesh>& meshes = model.meshes();
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    const SystemMesh& mesh = meshes[k];
    double delta = 0.0;
    for (int a = 0; a < 12; ++a) {
      if (mesh.dofs[a] >= 0) delta += mesh.G(0, a) * q(mesh.dofs[a]);
    }
    dte(static_cast<Eigen::Index>(k)) = delta - TransmissionError(mesh, theta)(0);
  }
}

void CalcElementForce(const SystemModel& model, ElementIndex e, const Eigen::Ref<const VectorX>& q,
                      const Eigen::Ref<const VectorX>& qdot, Eigen::Ref<VectorX> force) {
  const int num_elements = static_cast<int>(model.elements().size());
  GEARDYN_THROW_UNLESS(e.value() >= 0 && e.value() < num_elements,
                       "CalcElementForce: element index " << e.value() << " out of range [0, "
                                                          << num_elements << ")");
  CheckState(model, q, qdot, "CalcElementForce");
  const SystemElement& element = model.elements()[static_cast<std::size_t>(e.value())];
  const int m = static_cast<int>(element.dofs.size());
  GEARDYN_CHECK_SIZE(force.size(), m, "CalcElementForce: force");
  const bool damped = qdot.size() > 0 && element.damping.rows() == m;
  // f_e = K_e q_e + C_e q̇_e; the fixed coordinates (dof −1) are zero.
  for (int a = 0; a < m; ++a) {
    double f = 0.0;
    for (int b = 0; b < m; ++b) {
      const int d = element.dofs[static_cast<std::size_t>(b)];
      if (d < 0) continue;
      f += element.stiffness(a, b) * q(d);
      if (damped) f += element.damping(a, b) * qdot(d);
    }
    force(a) = f;
  }
}

const char* ToString(ProbeKind kind) {
  switch (kind) {
    case ProbeKind::kMeshDte:
      return "dte";
    case ProbeKind::kMeshTorsionalTe:
      return "torsional_te";
    case ProbeKind::kMeshLoadedTe:
      return "loaded_te";
  }
  return "unknown";
}

ProbeMatrix MakeProbeMatrix(const SystemModel& model, const std::vector<ProbeKind>& kinds) {
  ProbeMatrix probes;
  std::vector<Eigen::Triplet<double>> triplets;
  const std::vector<SystemMesh>& meshes = model.meshes();
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    const SystemMesh& mesh = meshes[k];
    for (const ProbeKind kind : kinds) {
      const int row = probes.rows();
      for (int a = 0; a < 12; ++a) {
        const bool rotation_about_axis = a == kThetaZi || a == kThetaZj;
        if (kind == ProbeKind::kMeshTorsionalTe && !rotation_about_axis) continue;
        if (mesh.dofs[a] >= 0 && mesh.G(0, a) != 0.0) {
          triplets.emplace_back(row, mesh.dofs[a], mesh.G(0, a));
        }
      }
      probes.names.push_back(std::string(ToString(kind)) + ":" + mesh.name);
      probes.kinds.push_back(kind);
      probes.meshes.push_back(static_cast<int>(k));
      probes.has_offset.push_back(kind != ProbeKind::kMeshLoadedTe && HasTransmissionError(mesh));
    }
  }
  probes.P.resize(probes.rows(), model.num_dofs());
  probes.P.setFromTriplets(triplets.begin(), triplets.end());  // duplicates (same DOF) add up
  return probes;
}

void EvalProbeOffset(const SystemModel& model, const ProbeMatrix& probes, double theta,
                     Eigen::Ref<VectorX> offset) {
  GEARDYN_THROW_UNLESS(std::isfinite(theta),
                       "EvalProbeOffset: theta must be finite, got " << theta);
  GEARDYN_CHECK_SIZE(offset.size(), probes.rows(), "EvalProbeOffset: offset");
  for (int r = 0; r < probes.rows(); ++r) {
    const std::size_t row = static_cast<std::size_t>(r);
    GEARDYN_THROW_UNLESS(probes.meshes[row] >= 0 && probes.meshes[row] < model.num_meshes(),
                         "EvalProbeOffset: the probe matrix does not fit the model (row "
                             << r << " names mesh " << probes.meshes[row] << ")");
    offset(r) = probes.has_offset[row]
                    ? TransmissionError(
                          model.meshes()[static_cast<std::size_t>(probes.meshes[row])], theta)(0)
                    : 0.0;
  }
}

ProbeValues EvalProbes(const SystemModel& model, double theta, const Eigen::Ref<const VectorX>& q,
                       const Eigen::Ref<const VectorX>& qdot) {
  ProbeWorkspace ws(model);
  ProbeValues values;
  for (int k = 0; k < model.num_meshes(); ++k) {
    values.meshes.push_back(EvalMeshProbe(model, ws, MeshIndex(k), theta, q, qdot));
  }
  const std::vector<SystemElement>& elements = model.elements();
  for (std::size_t e = 0; e < elements.size(); ++e) {
    VectorX f(static_cast<Eigen::Index>(elements[e].dofs.size()));
    CalcElementForce(model, ElementIndex(static_cast<int>(e)), q, qdot, f);
    values.element_forces.push_back(std::move(f));
  }
  return values;
}

}  // namespace geardyn
