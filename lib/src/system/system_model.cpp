#include "geardyn/system/system_model.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>
#include <type_traits>

#include "geardyn/common/check.hpp"
#include "geardyn/common/overloaded.hpp"
#include "system_model_data.hpp"

namespace geardyn {
namespace {

// Largest |value| of channel c over every stored value of the coefficient (an upper bound of
// |f_c(θ)| for constant, piecewise, table; for Fourier the sum of |mean| and 2|c_n|).
double ChannelBound(const Coefficient& coef, int c) {
  return std::visit(
      Overloaded{
          [c](const ConstantCoefficient& k) { return std::abs(k.values()(c)); },
          [c](const PiecewiseConstantCoefficient& k) {
            return k.values().row(c).cwiseAbs().maxCoeff();
          },
          [c](const FourierCoefficient& k) {
            double s = std::abs(k.mean()(c));
            if (k.num_terms() > 0) s += 2.0 * k.harmonics().row(c).cwiseAbs().sum();
            return s;
          },
          [c](const TableCoefficient& k) { return k.samples().row(c).cwiseAbs().maxCoeff(); },
      },
      coef);
}

constexpr double kNegligible = 1e-12;  // relative size below which a coupling counts as zero

// Union-find over DOFs.
struct DisjointSets {
  explicit DisjointSets(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int Find(int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void Union(int a, int b) {
    a = Find(a);
    b = Find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
  std::vector<int> parent;
};

void UnionPattern(const SparseMatrix& a, DisjointSets& sets) {
  const VectorX diag = a.diagonal().cwiseAbs();
  for (int col = 0; col < a.outerSize(); ++col) {
    for (SparseMatrix::InnerIterator it(a, col); it; ++it) {
      if (it.row() == col || it.value() == 0.0) continue;
      const double scale = std::sqrt(diag(it.row()) * diag(col));
      if (std::abs(it.value()) > kNegligible * scale) sets.Union(static_cast<int>(it.row()), col);
    }
  }
}

}  // namespace

namespace internal {

std::uint64_t NextModelId() {
  static std::atomic<std::uint64_t> next{1};
  return next++;
}

CorePattern CalcCorePattern(const MeshCore& core) {
  return std::visit(Overloaded{
                        [](const LinearMeshCore& k) {
                          CorePattern p;
                          const double c0 = ChannelBound(k.stiffness(), 0);
                          p.eta = c0 > 0.0;
                          if (k.level() == MeshCoreLevel::kBlankenshipSingh) {
                            const double c1 = ChannelBound(k.stiffness(), 1);
                            const double c2 = ChannelBound(k.stiffness(), 2);
                            p.zeta = c2 > 0.0;
                            p.cross = c1 > kNegligible * std::sqrt(c0 * c2);
                          }
                          return p;
                        },
                        [](const SliceMeshCore& k) {
                          CorePattern p;
                          p.eta = true;
                          p.zeta = k.sigma().cwiseAbs().maxCoeff() > 0.0;
                          p.cross = p.zeta;
                          return p;
                        },
                        [](const std::shared_ptr<const NonlinearMeshCore>&) {
                          CorePattern p;
                          p.eta = p.zeta = p.cross = p.all_coordinates = true;
                          return p;
                        },
                    },
                    core);
}

Matrix2 CalcMeanCoreStiffness(const MeshCore& core) {
  return std::visit(Overloaded{
                        [](const LinearMeshCore& k) -> Matrix2 {
                          return EvalStiffnessCore(MakeMeanLinearMeshCore(k), 0.0);
                        },
                        [](const SliceMeshCore& k) -> Matrix2 {
                          const VectorX kbar = Mean(k.stiffness());
                          const double c0 = kbar.sum();
                          const double c1 = kbar.dot(k.sigma());
                          const double c2 = kbar.dot(k.sigma().cwiseAbs2());
                          Matrix2 out;
                          out << c0, -c1, -c1, c2;
                          return out;
                        },
                        [](const std::shared_ptr<const NonlinearMeshCore>&) -> Matrix2 {
                          return Matrix2::Zero();
                        },
                    },
                    core);
}

void ComputeFacts(SystemModel::Data& data) {
  data.time_dependence = TimeDependence::kConstant;
  data.period_meshes = 1;
  for (const SystemMesh& mesh : data.meshes) {
    data.time_dependence = Combine(data.time_dependence, Classify(mesh.core));
    data.period_meshes = std::lcm(data.period_meshes, PeriodMeshes(mesh.core));
  }

  const int n = data.dof_map.num_dofs();
  DisjointSets sets(n);
  UnionPattern(data.mass, sets);
  UnionPattern(data.stiffness0, sets);
  UnionPattern(data.damping0, sets);
  for (const SystemMesh& mesh : data.meshes) {
    const CorePattern p = CalcCorePattern(mesh.core);
    std::array<std::vector<int>, 2> row_dofs;
    for (int r = 0; r < 2; ++r) {
      const bool active = p.all_coordinates || (r == 0 ? p.eta : p.zeta);
      if (!active) continue;
      const double row_max = mesh.G.row(r).cwiseAbs().maxCoeff();
      for (int k = 0; k < 12; ++k) {
        if (mesh.dofs[k] < 0) continue;
        if (p.all_coordinates || std::abs(mesh.G(r, k)) > kNegligible * row_max) {
          row_dofs[r].push_back(mesh.dofs[k]);
        }
      }
    }
    if (p.all_coordinates) {
      for (int k = 0; k < 12; ++k) {
        if (mesh.dofs[k] >= 0) row_dofs[0].push_back(mesh.dofs[k]);
      }
    }
    for (int r = 0; r < 2; ++r) {
      for (std::size_t a = 1; a < row_dofs[r].size(); ++a)
        sets.Union(row_dofs[r][0], row_dofs[r][a]);
    }
    if (p.cross && !row_dofs[0].empty() && !row_dofs[1].empty()) {
      sets.Union(row_dofs[0][0], row_dofs[1][0]);
    }
  }
  std::vector<int> block_of_root(n, -1);
  data.blocks.clear();
  for (int i = 0; i < n; ++i) {
    const int root = sets.Find(i);
    if (block_of_root[root] < 0) {
      block_of_root[root] = static_cast<int>(data.blocks.size());
      data.blocks.emplace_back();
    }
    data.blocks[block_of_root[root]].push_back(i);
  }
}

}  // namespace internal

const char* ToString(StorageKind kind) { return kind == StorageKind::kDense ? "dense" : "sparse"; }

const char* ToString(ElementKind kind) {
  switch (kind) {
    case ElementKind::kBearing:
      return "bearing";
    case ElementKind::kShaft:
      return "shaft";
    case ElementKind::kCoupling:
      return "coupling";
    case ElementKind::kSpring:
      return "spring";
    case ElementKind::kMeshPreload:
      return "mesh preload";
  }
  return "?";
}

SystemModel::SystemModel() {
  auto data = std::make_shared<Data>();
  data->id = internal::NextModelId();
  data->mass.resize(0, 0);
  data->stiffness0.resize(0, 0);
  data->damping0.resize(0, 0);
  data_ = std::move(data);
}

SystemModel::SystemModel(std::shared_ptr<const Data> data) : data_(std::move(data)) {
  GEARDYN_DEMAND(data_ != nullptr);
}

int SystemModel::num_dofs() const { return data_->dof_map.num_dofs(); }
int SystemModel::num_bodies() const { return data_->dof_map.num_bodies(); }
const DofMap& SystemModel::dof_map() const { return data_->dof_map; }
std::uint64_t SystemModel::id() const { return data_->id; }
const SparseMatrix& SystemModel::mass() const { return data_->mass; }
const SparseMatrix& SystemModel::constant_stiffness() const { return data_->stiffness0; }
const SparseMatrix& SystemModel::constant_damping() const { return data_->damping0; }
const VectorX& SystemModel::constant_load() const { return data_->load0; }
MatrixX SystemModel::DenseMass() const { return MatrixX(data_->mass); }
MatrixX SystemModel::DenseConstantStiffness() const { return MatrixX(data_->stiffness0); }
MatrixX SystemModel::DenseConstantDamping() const { return MatrixX(data_->damping0); }
const std::vector<SystemMesh>& SystemModel::meshes() const { return data_->meshes; }
int SystemModel::num_meshes() const { return static_cast<int>(data_->meshes.size()); }
const std::vector<SystemElement>& SystemModel::elements() const { return data_->elements; }
const std::vector<SystemLoad>& SystemModel::loads() const { return data_->loads; }
const std::vector<SystemHarmonicLoad>& SystemModel::harmonic_loads() const {
  return data_->harmonic_loads;
}
double SystemModel::rayleigh_alpha() const { return data_->rayleigh_alpha; }
double SystemModel::rayleigh_beta() const { return data_->rayleigh_beta; }
double SystemModel::modal_damping_ratio() const { return data_->modal_zeta; }
TimeDependence SystemModel::time_dependence() const { return data_->time_dependence; }
std::int64_t SystemModel::period_meshes() const { return data_->period_meshes; }
const std::vector<std::vector<int>>& SystemModel::blocks() const { return data_->blocks; }
int SystemModel::num_blocks() const { return static_cast<int>(data_->blocks.size()); }
bool SystemModel::is_symmetric() const { return true; }
StorageKind SystemModel::storage_hint() const {
  return num_dofs() < kDenseDofThreshold ? StorageKind::kDense : StorageKind::kSparse;
}

SystemModel SystemModel::RestrictToBlock(int b) const {
  GEARDYN_THROW_UNLESS(b >= 0 && b < num_blocks(),
                       "block " << b << ": out of range [0, " << num_blocks() << ")");
  return Restrict(data_->blocks[b]);
}

SystemModel SystemModel::WithPhaseRatios(const std::vector<double>& ratios) const {
  GEARDYN_THROW_UNLESS(ratios.size() == data_->meshes.size(),
                       "ratios: one phase ratio per mesh wanted (" << data_->meshes.size()
                                                                   << "), got " << ratios.size());
  auto out = std::make_shared<Data>(*data_);
  for (std::size_t k = 0; k < ratios.size(); ++k) {
    GEARDYN_THROW_UNLESS(std::isfinite(ratios[k]) && ratios[k] > 0.0,
                         "ratios[" << k << "]: must be finite and > 0, got " << ratios[k]);
    out->meshes[k].phase_ratio = ratios[k];
  }
  out->id = internal::NextModelId();
  return SystemModel(std::move(out));
}

SystemModel SystemModel::WithAddedStiffness(const SparseMatrix& added) const {
  const int n = num_dofs();
  GEARDYN_THROW_UNLESS(added.rows() == n && added.cols() == n,
                       "added stiffness: size " << added.rows() << "×" << added.cols()
                                                << ", expected " << n << "×" << n);
  const MatrixX dense(added);
  GEARDYN_THROW_UNLESS(dense.allFinite(), "added stiffness: non-finite entry");
  const double scale = dense.cwiseAbs().maxCoeff();
  GEARDYN_THROW_UNLESS((dense - dense.transpose()).cwiseAbs().maxCoeff() <= 1e-12 * scale,
                       "added stiffness: not symmetric");
  auto out = std::make_shared<Data>(*data_);
  out->stiffness0 = SparseMatrix(out->stiffness0 + added);
  out->stiffness0.makeCompressed();
  internal::ComputeFacts(*out);
  out->id = internal::NextModelId();
  return SystemModel(std::move(out));
}

SystemModel SystemModel::RestrictToPlanar() const {
  std::vector<int> dofs;
  for (int i = 0; i < num_dofs(); ++i) {
    const BodyDof c = data_->dof_map.dof_component(i);
    if (c == BodyDof::kX || c == BodyDof::kY || c == BodyDof::kThetaZ) dofs.push_back(i);
  }
  return Restrict(dofs);
}

SystemModel SystemModel::Restrict(const std::vector<int>& dofs) const {
  const Data& in = *data_;
  auto out = std::make_shared<Data>();
  out->id = internal::NextModelId();
  out->dof_map = in.dof_map.Restrict(dofs);  // validates the indices
  const int n = num_dofs();
  const int m = static_cast<int>(dofs.size());
  std::vector<int> new_index(n, -1);
  for (int k = 0; k < m; ++k) new_index[dofs[k]] = k;

  SparseMatrix select(n, m);
  std::vector<Eigen::Triplet<double>> triplets;
  for (int k = 0; k < m; ++k) triplets.emplace_back(dofs[k], k, 1.0);
  select.setFromTriplets(triplets.begin(), triplets.end());
  const SparseMatrix select_t = select.transpose();
  out->mass = select_t * in.mass * select;
  out->stiffness0 = select_t * in.stiffness0 * select;
  out->damping0 = select_t * in.damping0 * select;
  out->load0 = select_t * in.load0;

  auto remap = [&](int i) { return i < 0 ? -1 : new_index[i]; };
  for (const SystemElement& e : in.elements) {
    SystemElement r = e;
    bool any = false;
    for (int& d : r.dofs) {
      d = remap(d);
      any = any || d >= 0;
    }
    if (any) out->elements.push_back(std::move(r));
  }
  for (const SystemMesh& mesh : in.meshes) {
    SystemMesh r = mesh;
    const internal::CorePattern p = internal::CalcCorePattern(mesh.core);
    bool any = false;
    for (int k = 0; k < 12; ++k) {
      r.dofs[k] = remap(r.dofs[k]);
      if (r.dofs[k] < 0) continue;
      const bool touches =
          p.all_coordinates || (p.eta && mesh.G(0, k) != 0.0) || (p.zeta && mesh.G(1, k) != 0.0);
      any = any || touches;
    }
    if (any) out->meshes.push_back(std::move(r));
  }
  for (const SystemLoad& load : in.loads) {
    SystemLoad r = load;
    bool any = false;
    for (int& d : r.dofs) {
      d = remap(d);
      any = any || (d >= 0);
    }
    if (any) out->loads.push_back(std::move(r));
  }
  for (const SystemHarmonicLoad& load : in.harmonic_loads) {
    SystemHarmonicLoad r = load;
    bool any = false;
    for (int& d : r.dofs) {
      d = remap(d);
      any = any || (d >= 0);
    }
    if (any) out->harmonic_loads.push_back(std::move(r));
  }
  out->rayleigh_alpha = in.rayleigh_alpha;
  out->rayleigh_beta = in.rayleigh_beta;
  out->modal_zeta = in.modal_zeta;
  internal::ComputeFacts(*out);
  return SystemModel(std::move(out));
}

std::int64_t OperatorPeriodMeshes(const SystemModel& model) {
  std::int64_t p = 1;
  for (const SystemMesh& mesh : model.meshes()) p = std::lcm(p, OperatorPeriodMeshes(mesh.core));
  // Every core's operator period divides its period, so P_K divides the model's P.
  GEARDYN_DEMAND(model.period_meshes() % p == 0);
  return p;
}

void AccumulateHarmonicLoads(const SystemModel& model, double theta, Eigen::Ref<VectorX> load) {
  for (const SystemHarmonicLoad& h : model.harmonic_loads()) {
    const double c = std::cos(h.order * theta), s = std::sin(h.order * theta);
    for (int a = 0; a < kBodyDofs; ++a) {
      if (h.dofs[a] >= 0) load(h.dofs[a]) += h.amplitude(a).real() * c - h.amplitude(a).imag() * s;
    }
  }
}

}  // namespace geardyn
