// Classification path of ComputeModes: kinetic-energy fractions per DOF kind and per body,
// strain-energy fractions per mesh and element, mode-type labels and multiplicity groups (the
// definitions are in the file comment of geardyn/analyses/modal.hpp).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "geardyn/common/check.hpp"
#include "modal/modal_internal.hpp"

namespace geardyn {

const char* ToString(PlanetaryModeType type) {
  switch (type) {
    case PlanetaryModeType::kRotational:
      return "rotational";
    case PlanetaryModeType::kTranslational:
      return "translational";
    case PlanetaryModeType::kPlanet:
      return "planet";
    case PlanetaryModeType::kMixed:
      return "mixed";
  }
  return "unknown";
}

}  // namespace geardyn

namespace geardyn::internal {
namespace {

// Relative size of K0 − Σ element stiffness above which the unowned stiffness gets its own
// strain-energy column "other" (sums of O(10) terms: round-off is ~1e-15).
constexpr double kOtherStiffnessTol = 1e-12;

// Sums φ_i A_ij φ_j over the entries (i, j) of A whose group(i) == group(j) into out(group).
void AccumulateBlockDiagonal(const SparseMatrix& A, const std::vector<int>& group,
                             const Eigen::Ref<const VectorX>& phi, Eigen::Ref<VectorX> out) {
  out.setZero();
  for (int j = 0; j < A.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      const int i = static_cast<int>(it.row());
      if (group[i] == group[j]) out(group[i]) += phi(i) * it.value() * phi(j);
    }
  }
}

// Fractions out / Σ out (all ≥ 0 up to round-off: clamped); zeros if the sum is 0.
void Normalize(Eigen::Ref<VectorX> values) {
  values = values.cwiseMax(0.0);
  const double total = values.sum();
  if (total > 0.0) values /= total;
}

ModeType LabelFromKinetic(const Eigen::Ref<const VectorX>& kinetic) {
  Eigen::Index dominant = 0;
  kinetic.maxCoeff(&dominant);
  switch (static_cast<DofKind>(dominant)) {
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

// Does K0 hold stiffness that no element owns (then strain fractions get an "other" column)?
bool HasUnownedStiffness(const SystemModel& model) {
  const int n = model.num_dofs();
  std::vector<Eigen::Triplet<double>> triplets;
  for (const SystemElement& e : model.elements()) {
    for (std::size_t a = 0; a < e.dofs.size(); ++a) {
      if (e.dofs[a] < 0) continue;
      for (std::size_t b = 0; b < e.dofs.size(); ++b) {
        if (e.dofs[b] < 0) continue;
        triplets.emplace_back(
            e.dofs[a], e.dofs[b],
            e.stiffness(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)));
      }
    }
  }
  SparseMatrix owned(n, n);
  owned.setFromTriplets(triplets.begin(), triplets.end());
  const SparseMatrix& k0 = model.constant_stiffness();
  const double scale = std::max(k0.norm(), owned.norm());
  return scale > 0.0 && SparseMatrix(k0 - owned).norm() > kOtherStiffnessTol * scale;
}

// DOF sets of the planetary labels (modal.hpp): axial/torsional and lateral DOFs of the central
// (non-planet) bodies, and every planet DOF.
enum PlanetarySet { kCentralAxial = 0, kCentralLateral = 1, kPlanetDofs = 2, kNumPlanetarySets };

// Lin & Parker (1999) labels per multiplicity group from the energies of the three DOF sets.
std::vector<PlanetaryModeType> LabelPlanetaryModes(const SystemModel& model, const MeanSystem& sys,
                                                   const MatrixX& shapes,
                                                   const std::vector<std::vector<int>>& groups) {
  const DofMap& dofs = model.dof_map();
  const int n = model.num_dofs();
  std::vector<int> set(n);
  for (int i = 0; i < n; ++i) {
    if (dofs.body_role(dofs.dof_body(i)) == BodyRole::kPlanet) {
      set[i] = kPlanetDofs;
    } else {
      const DofKind kind = dofs.dof_kind(i);
      const bool axial = kind == DofKind::kRotationAxial || kind == DofKind::kTranslationAxial;
      set[i] = axial ? kCentralAxial : kCentralLateral;
    }
  }
  std::vector<PlanetaryModeType> labels(static_cast<std::size_t>(shapes.cols()),
                                        PlanetaryModeType::kMixed);
  VectorX energy(kNumPlanetarySets), mode_energy(kNumPlanetarySets);
  for (const std::vector<int>& group : groups) {
    energy.setZero();
    for (int k : group) {
      AccumulateBlockDiagonal(sys.M, set, shapes.col(k), mode_energy);
      energy += mode_energy.cwiseMax(0.0);
    }
    const double central = energy(kCentralAxial) + energy(kCentralLateral);
    const double total = central + energy(kPlanetDofs);
    PlanetaryModeType type = PlanetaryModeType::kMixed;
    if (central <= kPlanetaryEnergyTol * total) {
      type = PlanetaryModeType::kPlanet;
    } else if (energy(kCentralLateral) <= kPlanetaryEnergyTol * central) {
      type = PlanetaryModeType::kRotational;
    } else if (energy(kCentralAxial) <= kPlanetaryEnergyTol * central) {
      type = PlanetaryModeType::kTranslational;
    }
    for (int k : group) labels[static_cast<std::size_t>(k)] = type;
  }
  return labels;
}

}  // namespace

std::vector<std::vector<int>> GroupMultiplicities(const VectorX& frequencies_hz, double rel_tol) {
  std::vector<std::vector<int>> groups;
  for (Eigen::Index k = 0; k < frequencies_hz.size(); ++k) {
    const bool same = k > 0 && std::abs(frequencies_hz(k) - frequencies_hz(k - 1)) <=
                                   rel_tol * std::max(frequencies_hz(k), frequencies_hz(k - 1));
    if (!same) groups.emplace_back();
    groups.back().push_back(static_cast<int>(k));
  }
  return groups;
}

void ClassifyModes(const SystemModel& model, const MeanSystem& sys, const MatrixX& shapes,
                   const VectorX& eigenvalues, ModalResult* result) {
  const int n = model.num_dofs();
  const Eigen::Index m = shapes.cols();
  GEARDYN_DEMAND(shapes.rows() == n && eigenvalues.size() == m);
  const DofMap& dofs = model.dof_map();

  std::vector<int> kind(n), body(n);
  for (int i = 0; i < n; ++i) {
    kind[i] = static_cast<int>(dofs.dof_kind(i));
    body[i] = dofs.dof_body(i).value();
  }

  // Strain owners: meshes, elements, then "other" when K0 has unowned stiffness.
  result->strain_names.clear();
  for (const SystemMesh& mesh : model.meshes()) result->strain_names.push_back("mesh:" + mesh.name);
  for (const SystemElement& e : model.elements()) {
    result->strain_names.push_back("element:" + e.name);
  }
  const bool other = HasUnownedStiffness(model);
  if (other) result->strain_names.emplace_back("other");
  const int num_meshes = model.num_meshes();
  const int num_owners = static_cast<int>(result->strain_names.size());

  result->kinetic_fractions.setZero(m, kNumDofKinds);
  result->body_kinetic_fractions.setZero(m, model.num_bodies());
  result->strain_fractions.setZero(m, num_owners);
  result->labels.assign(static_cast<std::size_t>(m), ModeType::kRigidBody);

  VectorX kinetic(kNumDofKinds), body_kinetic(model.num_bodies()), strain(num_owners);
  Vector12 local;
  for (Eigen::Index k = 0; k < m; ++k) {
    const auto phi = shapes.col(k);
    AccumulateBlockDiagonal(sys.M, kind, phi, kinetic);
    AccumulateBlockDiagonal(sys.M, body, phi, body_kinetic);
    Normalize(kinetic);
    Normalize(body_kinetic);
    result->kinetic_fractions.row(k) = kinetic.transpose();
    result->body_kinetic_fractions.row(k) = body_kinetic.transpose();

    if (eigenvalues(k) == 0.0) continue;  // rigid-body mode: no strain energy, label kRigidBody
    result->labels[k] = LabelFromKinetic(kinetic);
    strain.setZero();
    for (int c = 0; c < num_meshes; ++c) {
      const SystemMesh& mesh = model.meshes()[c];
      for (int a = 0; a < 12; ++a) local(a) = mesh.dofs[a] >= 0 ? phi(mesh.dofs[a]) : 0.0;
      strain(c) = local.dot(sys.mesh_stiffness[c] * local);
    }
    for (std::size_t e = 0; e < model.elements().size(); ++e) {
      const SystemElement& element = model.elements()[e];
      VectorX x(static_cast<Eigen::Index>(element.dofs.size()));
      for (std::size_t a = 0; a < element.dofs.size(); ++a) {
        x(static_cast<Eigen::Index>(a)) = element.dofs[a] >= 0 ? phi(element.dofs[a]) : 0.0;
      }
      strain(num_meshes + static_cast<Eigen::Index>(e)) = x.dot(element.stiffness * x);
    }
    const double total = phi.dot(sys.K * phi);
    if (other) strain(num_owners - 1) = std::max(total - strain.head(num_owners - 1).sum(), 0.0);
    Normalize(strain);
    result->strain_fractions.row(k) = strain.transpose();
  }
  result->planetary_labels.clear();
  if (dofs.num_planets() > 0) {
    result->planetary_labels = LabelPlanetaryModes(model, sys, shapes, result->multiplicity_groups);
  }
}

}  // namespace geardyn::internal
