#include "geardyn/system/system_builder.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <cmath>
#include <sstream>

#include "geardyn/common/check.hpp"
#include "geardyn/system/system_damping.hpp"
#include "geardyn/system/workspace.hpp"
#include "system_model_data.hpp"

namespace geardyn {
namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

constexpr double kSymmetryTol = 1e-10;  // relative to the largest entry
constexpr double kPsdTol = 1e-10;       // smallest eigenvalue ≥ −tol·largest

bool AllFinite(const MatrixX& a) { return a.allFinite(); }

double Asymmetry(const MatrixX& a) {
  const double scale = a.cwiseAbs().maxCoeff();
  if (scale == 0.0) return 0.0;
  return (a - a.transpose()).cwiseAbs().maxCoeff() / scale;
}

// Smallest eigenvalue relative to the largest |eigenvalue| (0 for a zero matrix).
double RelativeMinEigenvalue(const MatrixX& a) {
  if (a.size() == 0) return 0.0;
  Eigen::SelfAdjointEigenSolver<MatrixX> eig(0.5 * (a + a.transpose()), Eigen::EigenvaluesOnly);
  const double largest = eig.eigenvalues().cwiseAbs().maxCoeff();
  if (largest == 0.0) return 0.0;
  return eig.eigenvalues().minCoeff() / largest;
}

void CheckMatrix(const MatrixX& a, const std::string& what, bool psd) {
  GEARDYN_THROW_UNLESS(AllFinite(a), what << ": non-finite entry");
  const double asym = Asymmetry(a);
  GEARDYN_THROW_UNLESS(asym <= kSymmetryTol, what << ": not symmetric (max |A − Aᵀ| / max |A| = "
                                                  << asym << " > " << kSymmetryTol << ")");
  if (psd) {
    const double lmin = RelativeMinEigenvalue(a);
    GEARDYN_THROW_UNLESS(lmin >= -kPsdTol, what << ": not positive semi-definite (smallest "
                                                   "eigenvalue / largest = "
                                                << lmin << ")");
  }
}

void AddBlock(const MatrixX& a, const std::vector<int>& dofs, Triplets& t) {
  for (int c = 0; c < a.cols(); ++c) {
    if (dofs[c] < 0) continue;
    for (int r = 0; r < a.rows(); ++r) {
      if (dofs[r] < 0 || a(r, c) == 0.0) continue;
      t.emplace_back(dofs[r], dofs[c], a(r, c));
    }
  }
}

SparseMatrix FromTriplets(int n, const Triplets& t) {
  SparseMatrix a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  a.makeCompressed();
  return a;
}

}  // namespace

void SystemBuilder::CheckBody(BodyIndex b, const std::string& what) const {
  GEARDYN_THROW_UNLESS(
      b.value() >= 0 && b.value() < num_bodies(),
      what << ": unknown body index " << b.value() << " (bodies: " << num_bodies() << ")");
}

std::optional<BodyIndex> SystemBuilder::FindBody(const std::string& name) const {
  for (int b = 0; b < num_bodies(); ++b) {
    if (bodies_[b].name == name) return BodyIndex(b);
  }
  return std::nullopt;
}

BodyIndex SystemBuilder::AddBody(const std::string& name, const Matrix6& mass,
                                 const Vector3& position) {
  GEARDYN_THROW_UNLESS(!name.empty(), "body " << num_bodies() << ": empty name");
  GEARDYN_THROW_UNLESS(!FindBody(name), "body '" << name << "': duplicate name");
  const std::string what = "body '" + name + "' mass";
  CheckMatrix(mass, what, /*psd=*/true);
  GEARDYN_THROW_UNLESS(position.allFinite(), "body '" << name << "' position: non-finite");
  bodies_.push_back({name, mass, position, BodyRole::kOther});
  return BodyIndex(num_bodies() - 1);
}

void SystemBuilder::SetBodyRole(BodyIndex body, BodyRole role) {
  CheckBody(body, "SetBodyRole");
  bodies_[body.value()].role = role;
}

ElementIndex SystemBuilder::AddElement(const std::string& name, ElementKind kind,
                                       const std::vector<BodyIndex>& bodies,
                                       const MatrixX& stiffness, const MatrixX& damping,
                                       const MatrixX& mass) {
  const std::string what = std::string(ToString(kind)) + " '" + name + "'";
  GEARDYN_THROW_UNLESS(!name.empty(), ToString(kind) << " " << elements_.size() << ": empty name");
  for (const Element& e : elements_) {
    GEARDYN_THROW_UNLESS(e.name != name, what << ": duplicate element name");
  }
  GEARDYN_THROW_UNLESS(bodies.size() == 1 || bodies.size() == 2,
                       what << ": needs 1 (grounded) or 2 bodies, got " << bodies.size());
  for (BodyIndex b : bodies) CheckBody(b, what);
  GEARDYN_THROW_UNLESS(bodies.size() == 1 || bodies[0] != bodies[1],
                       what << ": connects body '" << bodies_[bodies[0]].name << "' to itself");
  const int size = kBodyDofs * static_cast<int>(bodies.size());
  GEARDYN_THROW_UNLESS(stiffness.rows() == size && stiffness.cols() == size,
                       what << " stiffness: size " << stiffness.rows() << "×" << stiffness.cols()
                            << ", expected " << size << "×" << size);
  // A preload's geometric stiffness softens (external meshes): symmetric, not PSD.
  CheckMatrix(stiffness, what + " stiffness", /*psd=*/kind != ElementKind::kMeshPreload);
  if (damping.size() > 0) {
    GEARDYN_THROW_UNLESS(damping.rows() == size && damping.cols() == size,
                         what << " damping: size " << damping.rows() << "×" << damping.cols()
                              << ", expected " << size << "×" << size);
    CheckMatrix(damping, what + " damping", /*psd=*/true);
  }
  if (mass.size() > 0) {
    GEARDYN_THROW_UNLESS(mass.rows() == size && mass.cols() == size,
                         what << " mass: size " << mass.rows() << "×" << mass.cols()
                              << ", expected " << size << "×" << size);
    CheckMatrix(mass, what + " mass", /*psd=*/true);
  }
  elements_.push_back({name, kind, bodies, stiffness, damping, mass});
  return ElementIndex(static_cast<int>(elements_.size()) - 1);
}

MeshIndex SystemBuilder::AddMesh(const std::string& name, BodyIndex body_i, BodyIndex body_j,
                                 const Matrix2x12& G, MeshCore core,
                                 std::optional<double> equivalent_mass, double phase_ratio,
                                 double phase_offset) {
  const std::string what = "mesh '" + name + "'";
  GEARDYN_THROW_UNLESS(!name.empty(), "mesh " << meshes_.size() << ": empty name");
  for (const Mesh& m : meshes_) {
    GEARDYN_THROW_UNLESS(m.name != name, what << ": duplicate mesh name");
  }
  CheckBody(body_i, what);
  CheckBody(body_j, what);
  GEARDYN_THROW_UNLESS(body_i != body_j,
                       what << ": meshes body '" << bodies_[body_i].name << "' with itself");
  GEARDYN_THROW_UNLESS(G.allFinite(), what << " G: non-finite entry");
  if (const auto* nl = std::get_if<std::shared_ptr<const NonlinearMeshCore>>(&core)) {
    GEARDYN_THROW_UNLESS(*nl != nullptr, what << ": null nonlinear core");
    GEARDYN_THROW_UNLESS(
        (*nl)->num_internal_coordinates() >= 0 &&
            (*nl)->num_coordinates() == 12 + (*nl)->num_internal_coordinates(),
        what << ": nonlinear core with " << (*nl)->num_coordinates() << " coordinates and "
             << (*nl)->num_internal_coordinates()
             << " internal ones; it must read the 12 of [q_i; q_j] followed by its internal ones");
  }
  if (equivalent_mass) {
    GEARDYN_THROW_UNLESS(
        std::isfinite(*equivalent_mass) && *equivalent_mass > 0.0,
        what << " equivalent_mass: must be finite and > 0, got " << *equivalent_mass << " kg");
  }
  // One check per argument, so that the message names the one that is wrong (issue 16).
  GEARDYN_THROW_UNLESS(std::isfinite(phase_ratio),
                       what << " phase_ratio: must be finite, got " << phase_ratio);
  GEARDYN_THROW_UNLESS(std::isfinite(phase_offset),
                       what << " phase_offset: must be finite, got " << phase_offset << " rad");
  meshes_.push_back(
      {name, body_i, body_j, G, std::move(core), equivalent_mass, phase_ratio, phase_offset});
  return MeshIndex(static_cast<int>(meshes_.size()) - 1);
}

void SystemBuilder::AddTorque(BodyIndex body, const Vector6& generalized_force,
                              const std::string& name) {
  const std::string label = name.empty() ? "load " + std::to_string(loads_.size()) : name;
  CheckBody(body, "load '" + label + "'");
  GEARDYN_THROW_UNLESS(generalized_force.allFinite(), "load '" << label << "': non-finite value");
  loads_.push_back({label, body, generalized_force});
}

void SystemBuilder::AddHarmonicLoad(BodyIndex body, const Vector6c& amplitude, int order,
                                    const std::string& name) {
  const std::string label =
      name.empty() ? "harmonic load " + std::to_string(harmonic_loads_.size()) : name;
  CheckBody(body, "harmonic load '" + label + "'");
  GEARDYN_THROW_UNLESS(amplitude.allFinite(),
                       "harmonic load '" << label << "' amplitude: non-finite value");
  GEARDYN_THROW_UNLESS(order >= 1, "harmonic load '" << label
                                                     << "' order: must be an integer >= 1 (a "
                                                        "harmonic of the mesh frequency), got "
                                                     << order);
  harmonic_loads_.push_back({label, body, amplitude, order});
}

void SystemBuilder::SetRayleighDamping(double alpha, double beta) {
  GEARDYN_THROW_UNLESS(std::isfinite(alpha) && alpha >= 0.0,
                       "rayleigh alpha: must be finite and ≥ 0, got " << alpha);
  GEARDYN_THROW_UNLESS(std::isfinite(beta) && beta >= 0.0,
                       "rayleigh beta: must be finite and ≥ 0, got " << beta);
  GEARDYN_THROW_UNLESS(!damping_.has_modal(), "rayleigh damping: modal damping ratio already set");
  damping_.rayleigh_alpha = alpha;
  damping_.rayleigh_beta = beta;
}

void SystemBuilder::SetModalDampingRatio(double zeta) {
  GEARDYN_THROW_UNLESS(std::isfinite(zeta) && zeta >= 0.0 && zeta < 1.0,
                       "modal damping ratio: must be in [0, 1), got " << zeta);
  GEARDYN_THROW_UNLESS(!damping_.has_rayleigh(),
                       "modal damping ratio: Rayleigh damping already set");
  damping_.modal_ratio = zeta;
}

void SystemBuilder::SetSystemDamping(const SystemDamping& damping) {
  std::string why;
  GEARDYN_THROW_UNLESS(damping.IsValid(&why), why);
  damping_ = damping;
}

SystemModel SystemBuilder::Build() const {
  GEARDYN_THROW_UNLESS(!bodies_.empty(), "system: no bodies");
  auto data = std::make_shared<SystemModel::Data>();
  data->id = internal::NextModelId();
  std::vector<std::string> names;
  std::vector<BodyRole> roles;
  for (const Body& b : bodies_) {
    names.push_back(b.name);
    roles.push_back(b.role);
  }
  data->dof_map = DofMap(names, roles);
  const int n = data->dof_map.num_dofs();

  auto body_dofs = [](const std::vector<BodyIndex>& bodies) {
    std::vector<int> dofs;
    for (BodyIndex b : bodies) {
      for (int c = 0; c < kBodyDofs; ++c) dofs.push_back(kBodyDofs * b.value() + c);
    }
    return dofs;
  };

  Triplets mass_t, stiffness_t, damping_t;
  std::vector<bool> referenced(n, false);
  for (int b = 0; b < num_bodies(); ++b) {
    AddBlock(bodies_[b].mass, body_dofs({BodyIndex(b)}), mass_t);
  }
  for (const Element& e : elements_) {
    SystemElement se;
    se.name = e.name;
    se.kind = e.kind;
    se.bodies = e.bodies;
    se.dofs = body_dofs(e.bodies);
    se.stiffness = e.stiffness;
    se.damping = e.damping.size() > 0 ? e.damping : MatrixX::Zero(se.dofs.size(), se.dofs.size());
    se.mass = e.mass;
    AddBlock(se.stiffness, se.dofs, stiffness_t);
    AddBlock(se.damping, se.dofs, damping_t);
    if (se.mass.size() > 0) AddBlock(se.mass, se.dofs, mass_t);
    for (std::size_t k = 0; k < se.dofs.size(); ++k) {
      if (se.stiffness.row(k).cwiseAbs().maxCoeff() > 0.0 ||
          se.damping.row(k).cwiseAbs().maxCoeff() > 0.0) {
        referenced[se.dofs[k]] = true;
      }
    }
    data->elements.push_back(std::move(se));
  }
  data->mass = FromTriplets(n, mass_t);
  data->stiffness0 = FromTriplets(n, stiffness_t);
  data->damping0 = FromTriplets(n, damping_t);

  // Meshes: DOFs, resolved damping, mean core.
  for (const Mesh& m : meshes_) {
    SystemMesh sm{.name = m.name, .body_i = m.body_i, .body_j = m.body_j, .core = m.core};
    const std::vector<int> dofs = body_dofs({m.body_i, m.body_j});
    for (int k = 0; k < 12; ++k) {
      sm.dofs[k] = dofs[k];
      if (m.G.col(k).cwiseAbs().maxCoeff() > 0.0) referenced[dofs[k]] = true;
    }
    sm.G = m.G;
    sm.phase_ratio = m.phase_ratio;
    sm.phase_offset = m.phase_offset;
    sm.mean_core_stiffness = internal::CalcMeanCoreStiffness(m.core);
    data->meshes.push_back(std::move(sm));
  }

  // Mass: every DOF must carry mass; then positive definite.
  // The diagonal of the sparse M directly: densifying it first (MatrixX(mass).diagonal()) cost
  // O(n²) memory and threw std::bad_alloc at 10⁵ DOFs (stress suite, issue 16).
  const VectorX mass_diag = data->mass.diagonal();
  for (int i = 0; i < n; ++i) {
    GEARDYN_THROW_UNLESS(
        mass_diag(i) > 0.0,
        "DOF " << data->dof_map.dof_name(i) << ": zero mass"
               << (referenced[i] ? " (referenced by an element or mesh; add inertia or a "
                                   "consistent element mass)"
                                 : " and no element or mesh references it (unreferenced DOF "
                                   "with zero mass: give the body inertia or remove the DOF)"));
  }
  {
    Eigen::SimplicialLLT<SparseMatrix> llt(data->mass);
    GEARDYN_THROW_UNLESS(llt.info() == Eigen::Success,
                         "system mass matrix: not positive definite (check the bodies' 6×6 "
                         "mass matrices and element masses)");
  }

  // Mesh equivalent masses and damping coefficients.
  for (std::size_t k = 0; k < meshes_.size(); ++k) {
    SystemMesh& sm = data->meshes[k];
    const Mesh& m = meshes_[k];
    double m_e = m.equivalent_mass.value_or(0.0);
    if (!m.equivalent_mass) {
      MatrixX m_pair(12, 12);
      for (int a = 0; a < 12; ++a) {
        for (int b = 0; b < 12; ++b) m_pair(a, b) = data->mass.coeff(sm.dofs[a], sm.dofs[b]);
      }
      const Eigen::Matrix<double, 12, 1> g = sm.G.row(0).transpose();
      const double flexibility = g.dot(m_pair.ldlt().solve(g));
      m_e = (std::isfinite(flexibility) && flexibility > 0.0) ? 1.0 / flexibility : 0.0;
    }
    sm.equivalent_mass = m_e;
    sm.damping_coefficient = std::visit(
        [&](const auto& core) -> double {
          using T = std::decay_t<decltype(core)>;
          if constexpr (std::is_same_v<T, std::shared_ptr<const NonlinearMeshCore>>) {
            return 0.0;
          } else {
            if (core.damping().kind != MeshDamping::Kind::kRatio) {
              return ResolveDampingCoefficient(core, 1.0);
            }
            GEARDYN_THROW_UNLESS(m_e > 0.0, "mesh '" << m.name
                                                     << "': damping ratio needs a positive "
                                                        "equivalent mass, got "
                                                     << m_e << " kg");
            return ResolveDampingCoefficient(core, m_e);
          }
        },
        sm.core);
  }

  // Loads.
  data->load0 = VectorX::Zero(n);
  for (const Load& l : loads_) {
    SystemLoad sl;
    sl.name = l.name;
    sl.body = l.body;
    sl.force = l.force;
    for (int c = 0; c < kBodyDofs; ++c) {
      sl.dofs[c] = kBodyDofs * l.body.value() + c;
      data->load0(sl.dofs[c]) += l.force(c);
    }
    data->loads.push_back(std::move(sl));
  }
  for (const HarmonicLoad& l : harmonic_loads_) {
    SystemHarmonicLoad sl;
    sl.name = l.name;
    sl.body = l.body;
    sl.amplitude = l.amplitude;
    sl.order = l.order;
    for (int c = 0; c < kBodyDofs; ++c) sl.dofs[c] = kBodyDofs * l.body.value() + c;
    data->harmonic_loads.push_back(std::move(sl));
  }

  internal::ComputeFacts(*data);  // blocks before Rayleigh/modal damping (which keep them)

  // Rayleigh/modal damping keeps the blocks (it couples DOFs of one block only).
  return AddSystemDamping(SystemModel(std::move(data)), damping_);
}

}  // namespace geardyn
