#include "geardyn/analyses/mode_matching.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <tuple>

#include "geardyn/common/check.hpp"

namespace geardyn {

bool ModeMatchingOptions::IsValid(std::string* why) const {
  if (!(cluster_rel_tol >= 0.0 && cluster_rel_tol < 0.1)) {
    if (why) {
      std::ostringstream s;
      s << "cluster_rel_tol: must be in [0, 0.1), got " << cluster_rel_tol;
      *why = s.str();
    }
    return false;
  }
  if (!(mac_threshold > 0.0 && mac_threshold <= 1.0)) {
    if (why) {
      std::ostringstream s;
      s << "mac_threshold: must be in (0, 1], got " << mac_threshold;
      *why = s.str();
    }
    return false;
  }
  return true;
}

namespace {

// Clusters of near-repeated frequencies: consecutive modes (ascending f) whose relative gap is
// at most tol, plus the result's multiplicity groups. Returns the cluster id of every mode.
std::vector<int> Clusters(const ModalResult& r, double tol) {
  const int m = static_cast<int>(r.frequencies_hz.size());
  std::vector<int> id(m);
  for (int k = 0; k < m; ++k) id[k] = k;
  const auto root = [&](int k) {
    while (id[k] != k) k = id[k] = id[id[k]];
    return k;
  };
  const auto join = [&](int a, int b) { id[root(a)] = root(b); };
  std::vector<int> order(m);
  for (int k = 0; k < m; ++k) order[k] = k;
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return r.frequencies_hz(a) < r.frequencies_hz(b); });
  for (int k = 0; k + 1 < m; ++k) {
    const double fa = r.frequencies_hz(order[k]), fb = r.frequencies_hz(order[k + 1]);
    if (std::abs(fb - fa) <= tol * std::max(std::abs(fa), std::abs(fb)))
      join(order[k], order[k + 1]);
  }
  for (const std::vector<int>& g : r.multiplicity_groups) {
    for (std::size_t k = 1; k < g.size(); ++k) {
      if (g[k] < m && g[0] < m) join(g[0], g[k]);
    }
  }
  for (int k = 0; k < m; ++k) id[k] = root(k);
  return id;
}

// Squared norm of each column's projection on its cluster's span, from the squared products
// (cross = (φ_iᵀMψ_j)², clusters of the rows).
MatrixX ClusterProjection(const MatrixX& squared, const std::vector<int>& row_cluster) {
  MatrixX out = squared;
  const int rows = static_cast<int>(squared.rows());
  for (int i = 0; i < rows; ++i) {
    Eigen::RowVectorXd sum = Eigen::RowVectorXd::Zero(squared.cols());
    for (int k = 0; k < rows; ++k) {
      if (row_cluster[k] == row_cluster[i]) sum += squared.row(k);
    }
    out.row(i) = sum;
  }
  return out;
}

MatrixX MacMatrix(const ModalResult& reference, const ModalResult& other, const SparseMatrix& mass,
                  double cluster_rel_tol) {
  const Eigen::Index n = mass.rows();
  const Eigen::Index m_ref = reference.frequencies_hz.size();
  const Eigen::Index m_other = other.frequencies_hz.size();
  GEARDYN_THROW_UNLESS(reference.shapes.rows() == n && reference.shapes.cols() == m_ref,
                       "reference: mode shapes ("
                           << n << " x " << m_ref << ") needed for the MAC, got "
                           << reference.shapes.rows() << " x " << reference.shapes.cols());
  GEARDYN_THROW_UNLESS(other.shapes.rows() == n && other.shapes.cols() == m_other,
                       "other: mode shapes (" << n << " x " << m_other
                                              << ") needed for the MAC, got " << other.shapes.rows()
                                              << " x " << other.shapes.cols());
  // Normalize both sets with M (they are M-orthonormal already; this keeps the MAC in [0, 1]
  // for shapes that are not, e.g. from another solver).
  const auto normalized = [&](const MatrixX& shapes) {
    MatrixX out = shapes;
    for (Eigen::Index k = 0; k < out.cols(); ++k) {
      const double norm2 = out.col(k).dot(mass * out.col(k));
      out.col(k) /= norm2 > 0.0 ? std::sqrt(norm2) : 1.0;
    }
    return out;
  };
  const MatrixX phi = normalized(reference.shapes);
  const MatrixX psi = normalized(other.shapes);
  const MatrixX squared = (phi.transpose() * (mass * psi)).cwiseAbs2();  // (φ_iᵀ M ψ_j)²
  // ψ_j on the span of φ_i's cluster, and φ_i on the span of ψ_j's cluster: the larger.
  const MatrixX by_reference = ClusterProjection(squared, Clusters(reference, cluster_rel_tol));
  const MatrixX by_other =
      ClusterProjection(squared.transpose(), Clusters(other, cluster_rel_tol)).transpose();
  return by_reference.cwiseMax(by_other).cwiseMin(1.0);
}

}  // namespace

MatrixX CalcModalAssuranceMatrix(const ModalResult& reference, const ModalResult& other,
                                 const SparseMatrix& mass, const ModeMatchingOptions& options) {
  std::string why;
  GEARDYN_THROW_UNLESS(options.IsValid(&why), why);
  return MacMatrix(reference, other, mass, options.cluster_rel_tol);
}

ModeMatching MatchModesByMac(const ModalResult& reference, const ModalResult& other,
                             const SparseMatrix& mass, const ModeMatchingOptions& options) {
  std::string why;
  GEARDYN_THROW_UNLESS(options.IsValid(&why), why);
  const MatrixX mac = MacMatrix(reference, other, mass, options.cluster_rel_tol);
  const int m_ref = static_cast<int>(mac.rows());
  const int m_other = static_cast<int>(mac.cols());
  ModeMatching out;
  out.matches.resize(m_ref);
  for (int i = 0; i < m_ref; ++i) {
    ModeMatch& m = out.matches[i];
    m.reference = i;
    m.reference_hz = reference.frequencies_hz(i);
    m.other_hz = std::numeric_limits<double>::quiet_NaN();
    m.relative_difference = std::numeric_limits<double>::quiet_NaN();
    if (m_other > 0) {
      Eigen::Index best = 0;
      m.mac = mac.row(i).maxCoeff(&best);
      m.best_other = static_cast<int>(best);
    }
  }
  // Greedy assignment by decreasing MAC (ties: lower reference index, then lower other index).
  std::vector<std::tuple<double, int, int>> pairs;
  for (int i = 0; i < m_ref; ++i) {
    for (int j = 0; j < m_other; ++j) {
      if (mac(i, j) >= options.mac_threshold) pairs.emplace_back(mac(i, j), i, j);
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) {
    if (std::get<0>(a) != std::get<0>(b)) return std::get<0>(a) > std::get<0>(b);
    if (std::get<1>(a) != std::get<1>(b)) return std::get<1>(a) < std::get<1>(b);
    return std::get<2>(a) < std::get<2>(b);
  });
  std::vector<bool> ref_used(m_ref, false), other_used(m_other, false);
  std::vector<int> assigned(m_ref, -1);
  for (const auto& [value, i, j] : pairs) {
    if (ref_used[i] || other_used[j]) continue;
    ref_used[i] = other_used[j] = true;
    assigned[i] = j;
  }
  // Inside a cluster of near-repeated reference frequencies the assignment is arbitrary (all
  // members have the same subspace MAC): pair the members and their matches in frequency order.
  const std::vector<int> cluster = Clusters(reference, options.cluster_rel_tol);
  for (int c = 0; c < m_ref; ++c) {
    std::vector<int> members, matched;
    for (int i = 0; i < m_ref; ++i) {
      if (cluster[i] == c && assigned[i] >= 0) {
        members.push_back(i);
        matched.push_back(assigned[i]);
      }
    }
    if (members.size() < 2) continue;
    const auto by_frequency = [](const ModalResult& r) {
      return [&r](int a, int b) { return r.frequencies_hz(a) < r.frequencies_hz(b); };
    };
    std::sort(members.begin(), members.end(), by_frequency(reference));
    std::sort(matched.begin(), matched.end(), by_frequency(other));
    for (std::size_t k = 0; k < members.size(); ++k) assigned[members[k]] = matched[k];
  }
  for (int i = 0; i < m_ref; ++i) {
    const int j = assigned[i];
    if (j < 0) continue;
    ModeMatch& m = out.matches[i];
    m.other = j;
    m.mac = mac(i, j);
    m.other_hz = other.frequencies_hz(j);
    if (m.reference_hz > 0.0) {
      m.relative_difference = (m.other_hz - m.reference_hz) / m.reference_hz;
      out.max_abs_relative_difference =
          std::max(out.max_abs_relative_difference, std::abs(m.relative_difference));
    } else if (m.other_hz == 0.0) {
      m.relative_difference = 0.0;  // both rigid-body modes
    }
    ++out.num_matched;
  }
  for (int j = 0; j < m_other; ++j) {
    if (!other_used[j]) out.extra.push_back(j);
  }
  return out;
}

}  // namespace geardyn
