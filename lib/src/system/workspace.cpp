#include "geardyn/system/workspace.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "geardyn/common/check.hpp"
#include "mesh_core_values.hpp"

namespace geardyn {
namespace {

using internal::kWantDamping;
using internal::kWantLoad;
using internal::kWantStiffness;
using internal::MeshCoreValues;

// The 2×2 stiffness, damping and load pair of mesh k at the system phase θ.
MeshCoreValues EvalCore(const SystemMesh& mesh, SystemWorkspace& ws, int k, double theta,
                        int want) {
  const int slice = ws.slice_workspace_of_mesh[k];
  return internal::EvalMeshCoreValues(mesh.core, mesh.damping_coefficient,
                                      slice >= 0 ? &ws.slice_workspaces[slice] : nullptr,
                                      mesh.MeshPhase(theta), want);
}

void CheckWorkspace(const SystemModel& model, const SystemWorkspace& ws, StorageKind storage,
                    const char* kernel) {
  GEARDYN_THROW_UNLESS(ws.IsCompatibleWith(model),
                       kernel << ": workspace was built for another model");
  GEARDYN_THROW_UNLESS(ws.storage == storage, kernel << ": needs a " << ToString(storage)
                                                     << " workspace, got a " << ToString(ws.storage)
                                                     << " one");
}

void ScatterDense(const SystemMesh& mesh, const Matrix12& block, MatrixX& out) {
  for (int b = 0; b < 12; ++b) {
    const int db = mesh.dofs[b];
    if (db < 0) continue;
    for (int a = 0; a < 12; ++a) {
      const int da = mesh.dofs[a];
      if (da >= 0) out(da, db) += block(a, b);
    }
  }
}

void ScatterSparse(const std::array<int, 144>& positions, const Matrix12& block,
                   SparseMatrix& out) {
  double* values = out.valuePtr();
  for (int b = 0; b < 12; ++b) {
    for (int a = 0; a < 12; ++a) {
      const int p = positions[12 * b + a];
      if (p >= 0) values[p] += block(a, b);
    }
  }
}

void CopyDense(const SparseMatrix& a, MatrixX& out) {
  out.setZero();
  for (int col = 0; col < a.outerSize(); ++col) {
    for (SparseMatrix::InnerIterator it(a, col); it; ++it) out(it.row(), col) += it.value();
  }
}

int FindPosition(const SparseMatrix& pattern, int row, int col) {
  const int* inner = pattern.innerIndexPtr();
  const int begin = pattern.outerIndexPtr()[col];
  const int end = pattern.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(inner + begin, inner + end, row);
  GEARDYN_DEMAND(it != inner + end && *it == row);
  return static_cast<int>(it - inner);
}

VectorX ValuesOnPattern(const SparseMatrix& pattern, const SparseMatrix& a) {
  VectorX values = VectorX::Zero(pattern.nonZeros());
  for (int col = 0; col < a.outerSize(); ++col) {
    for (SparseMatrix::InnerIterator it(a, col); it; ++it) {
      values(FindPosition(pattern, static_cast<int>(it.row()), col)) += it.value();
    }
  }
  return values;
}

void CheckTheta(double theta, const char* kernel) {
  GEARDYN_THROW_UNLESS(std::isfinite(theta), kernel << ": theta must be finite, got " << theta);
}

template <class Out, class Scatter>
void AddMeshBlocks(const SystemModel& model, SystemWorkspace& ws, double theta, bool mean,
                   bool damping, Out& out, Scatter scatter) {
  const std::vector<SystemMesh>& meshes = model.meshes();
  for (int k = 0; k < static_cast<int>(meshes.size()); ++k) {
    const SystemMesh& mesh = meshes[k];
    Matrix2 core;
    if (mean) {
      core = mesh.mean_core_stiffness;
    } else {
      const MeshCoreValues v =
          EvalCore(mesh, ws, k, theta, damping ? kWantDamping : kWantStiffness);
      core = damping ? v.damping : v.stiffness;
    }
    Matrix12& block = damping ? ws.mesh_damping[k] : ws.mesh_stiffness[k];
    block.noalias() = mesh.G.transpose() * core * mesh.G;
    scatter(k, block, out);
  }
}

}  // namespace

SystemWorkspace::SystemWorkspace(const SystemModel& model)
    : SystemWorkspace(model, model.storage_hint()) {}

SystemWorkspace::SystemWorkspace(const SystemModel& model, StorageKind storage_kind)
    : storage(storage_kind), model_id(model.id()), num_dofs(model.num_dofs()) {
  const int n = num_dofs;
  const std::vector<SystemMesh>& meshes = model.meshes();
  const int m = static_cast<int>(meshes.size());
  load = VectorX::Zero(n);
  mesh_stiffness.assign(m, Matrix12::Zero());
  mesh_damping.assign(m, Matrix12::Zero());
  mesh_load.assign(m, Vector12::Zero());
  slice_workspace_of_mesh.assign(m, -1);
  for (int k = 0; k < m; ++k) {
    if (const auto* slice = std::get_if<SliceMeshCore>(&meshes[k].core)) {
      slice_workspace_of_mesh[k] = static_cast<int>(slice_workspaces.size());
      slice_workspaces.emplace_back(*slice);
    }
  }
  if (storage == StorageKind::kDense) {
    stiffness = MatrixX::Zero(n, n);
    damping = MatrixX::Zero(n, n);
    return;
  }
  // Sparse: one pattern for K and C = K0 ∪ C0 ∪ every mesh block.
  std::vector<Eigen::Triplet<double>> t;
  auto add_pattern = [&t](const SparseMatrix& a) {
    for (int col = 0; col < a.outerSize(); ++col) {
      for (SparseMatrix::InnerIterator it(a, col); it; ++it) t.emplace_back(it.row(), col, 0.0);
    }
  };
  add_pattern(model.constant_stiffness());
  add_pattern(model.constant_damping());
  for (const SystemMesh& mesh : meshes) {
    for (int a = 0; a < 12; ++a) {
      for (int b = 0; b < 12; ++b) {
        if (mesh.dofs[a] >= 0 && mesh.dofs[b] >= 0) t.emplace_back(mesh.dofs[a], mesh.dofs[b], 0.0);
      }
    }
  }
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, 0.0);
  stiffness_sparse.resize(n, n);
  stiffness_sparse.setFromTriplets(t.begin(), t.end());
  stiffness_sparse.makeCompressed();
  damping_sparse = stiffness_sparse;
  mesh_value_positions.resize(m);
  for (int k = 0; k < m; ++k) {
    for (int b = 0; b < 12; ++b) {
      for (int a = 0; a < 12; ++a) {
        const int da = meshes[k].dofs[a];
        const int db = meshes[k].dofs[b];
        mesh_value_positions[k][12 * b + a] =
            (da >= 0 && db >= 0) ? FindPosition(stiffness_sparse, da, db) : -1;
      }
    }
  }
  constant_stiffness_values = ValuesOnPattern(stiffness_sparse, model.constant_stiffness());
  constant_damping_values = ValuesOnPattern(stiffness_sparse, model.constant_damping());
}

bool SystemWorkspace::IsCompatibleWith(const SystemModel& model) const {
  return model_id == model.id() && num_dofs == model.num_dofs();
}

const MatrixX& AssembleStiffness(const SystemModel& model, SystemWorkspace& ws, double theta) {
  CheckWorkspace(model, ws, StorageKind::kDense, "AssembleStiffness");
  CheckTheta(theta, "AssembleStiffness");
  CopyDense(model.constant_stiffness(), ws.stiffness);
  AddMeshBlocks(
      model, ws, theta, false, false, ws.stiffness,
      [&](int k, const Matrix12& b, MatrixX& out) { ScatterDense(model.meshes()[k], b, out); });
  return ws.stiffness;
}

const SparseMatrix& AssembleStiffnessSparse(const SystemModel& model, SystemWorkspace& ws,
                                            double theta) {
  CheckWorkspace(model, ws, StorageKind::kSparse, "AssembleStiffnessSparse");
  CheckTheta(theta, "AssembleStiffnessSparse");
  Eigen::Map<VectorX>(ws.stiffness_sparse.valuePtr(), ws.stiffness_sparse.nonZeros()) =
      ws.constant_stiffness_values;
  AddMeshBlocks(model, ws, theta, false, false, ws.stiffness_sparse,
                [&](int k, const Matrix12& b, SparseMatrix& out) {
                  ScatterSparse(ws.mesh_value_positions[k], b, out);
                });
  return ws.stiffness_sparse;
}

const MatrixX& AssembleMeanStiffness(const SystemModel& model, SystemWorkspace& ws) {
  CheckWorkspace(model, ws, StorageKind::kDense, "AssembleMeanStiffness");
  CopyDense(model.constant_stiffness(), ws.stiffness);
  AddMeshBlocks(
      model, ws, 0.0, true, false, ws.stiffness,
      [&](int k, const Matrix12& b, MatrixX& out) { ScatterDense(model.meshes()[k], b, out); });
  return ws.stiffness;
}

const SparseMatrix& AssembleMeanStiffnessSparse(const SystemModel& model, SystemWorkspace& ws) {
  CheckWorkspace(model, ws, StorageKind::kSparse, "AssembleMeanStiffnessSparse");
  Eigen::Map<VectorX>(ws.stiffness_sparse.valuePtr(), ws.stiffness_sparse.nonZeros()) =
      ws.constant_stiffness_values;
  AddMeshBlocks(model, ws, 0.0, true, false, ws.stiffness_sparse,
                [&](int k, const Matrix12& b, SparseMatrix& out) {
                  ScatterSparse(ws.mesh_value_positions[k], b, out);
                });
  return ws.stiffness_sparse;
}

const MatrixX& AssembleDamping(const SystemModel& model, SystemWorkspace& ws, double theta) {
  CheckWorkspace(model, ws, StorageKind::kDense, "AssembleDamping");
  CheckTheta(theta, "AssembleDamping");
  CopyDense(model.constant_damping(), ws.damping);
  AddMeshBlocks(
      model, ws, theta, false, true, ws.damping,
      [&](int k, const Matrix12& b, MatrixX& out) { ScatterDense(model.meshes()[k], b, out); });
  return ws.damping;
}

const SparseMatrix& AssembleDampingSparse(const SystemModel& model, SystemWorkspace& ws,
                                          double theta) {
  CheckWorkspace(model, ws, StorageKind::kSparse, "AssembleDampingSparse");
  CheckTheta(theta, "AssembleDampingSparse");
  Eigen::Map<VectorX>(ws.damping_sparse.valuePtr(), ws.damping_sparse.nonZeros()) =
      ws.constant_damping_values;
  AddMeshBlocks(model, ws, theta, false, true, ws.damping_sparse,
                [&](int k, const Matrix12& b, SparseMatrix& out) {
                  ScatterSparse(ws.mesh_value_positions[k], b, out);
                });
  return ws.damping_sparse;
}

namespace {
void ScatterLoad(const SystemMesh& mesh, const Vector12& f, VectorX& out) {
  for (int a = 0; a < 12; ++a) {
    if (mesh.dofs[a] >= 0) out(mesh.dofs[a]) += f(a);
  }
}
}  // namespace

const VectorX& AssembleLoad(const SystemModel& model, SystemWorkspace& ws, double theta) {
  GEARDYN_THROW_UNLESS(ws.IsCompatibleWith(model),
                       "AssembleLoad: workspace was built for another model");
  CheckTheta(theta, "AssembleLoad");
  ws.load = model.constant_load();
  const std::vector<SystemMesh>& meshes = model.meshes();
  for (int k = 0; k < static_cast<int>(meshes.size()); ++k) {
    const MeshCoreValues v = EvalCore(meshes[k], ws, k, theta, kWantLoad);
    ws.mesh_load[k].noalias() = meshes[k].G.transpose() * v.load;
    ScatterLoad(meshes[k], ws.mesh_load[k], ws.load);
  }
  AccumulateHarmonicLoads(model, theta, ws.load);
  return ws.load;
}

const VectorX& AssembleMeanLoad(const SystemModel& model, SystemWorkspace& ws,
                                int samples_per_period) {
  GEARDYN_THROW_UNLESS(ws.IsCompatibleWith(model),
                       "AssembleMeanLoad: workspace was built for another model");
  GEARDYN_THROW_UNLESS(samples_per_period >= 1,
                       "samples_per_period: must be ≥ 1, got " << samples_per_period);
  ws.load = model.constant_load();
  const std::vector<SystemMesh>& meshes = model.meshes();
  for (int k = 0; k < static_cast<int>(meshes.size()); ++k) {
    const auto* core = std::get_if<LinearMeshCore>(&meshes[k].core);
    if (core == nullptr || !core->has_transmission_error()) {
      ws.mesh_load[k].setZero();
      continue;
    }
    ws.mesh_load[k].noalias() =
        meshes[k].G.transpose() * CalcMeanTransmissionErrorLoad(*core, samples_per_period);
    ScatterLoad(meshes[k], ws.mesh_load[k], ws.load);
  }
  return ws.load;
}

}  // namespace geardyn
