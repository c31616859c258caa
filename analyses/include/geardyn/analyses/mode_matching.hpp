/// @file
/// @brief Matching the modes of two models of the same bodies by mode shape (the modal assurance
/// criterion, MAC), for comparing the levels of the model hierarchy (spec 01 §5, issue 15).
///
/// **MAC.** For M-orthonormal shapes φ (reference) and ψ (other) on the same coordinates and the
/// same mass matrix M (every mesh-model level has the same bodies, so the same M),
/// \f[ \mathrm{MAC}(φ, ψ) = \frac{(φ^T M ψ)^2}{(φ^T M φ)(ψ^T M ψ)} \in [0, 1], \f]
/// mass-weighted because the coordinates mix metres and radians (an unweighted MAC would depend
/// on the units). MAC = 1 for the same shape (up to sign), 0 for M-orthogonal shapes.
///
/// **Repeated and near-repeated frequencies.** Inside a cluster of (near-)repeated frequencies
/// (relative gaps ≤ cluster_rel_tol, or a ModalResult::multiplicity_group) the individual shapes
/// are an arbitrary basis of — or, for near-repeated ones, arbitrarily mixed by tiny changes in —
/// a subspace, so a mode is compared with the whole cluster: its MAC with a member is the squared
/// norm of its M-projection on the cluster, Σ_k (φ_kᵀMψ)², which does not depend on the basis;
/// clusters of either model are used (the larger value). The members of a reference cluster and
/// their matches are paired in frequency order.
///
/// **Assignment.** Greedy by decreasing MAC: the pair (reference i, other j) with the largest MAC
/// is matched first, then the next among the unmatched ones, as long as MAC ≥ threshold. A
/// reference mode left unmatched is *absent* from the other model (e.g. an axial or rocking mode of
/// a 6-DOF model that a torsional model cannot represent); an other-model mode left unmatched is
/// *extra*. Both are listed, never dropped.
#pragma once

#include <vector>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/common/eigen_types.hpp"

namespace geardyn {

/// @brief One reference mode and its match in the other model.
struct ModeMatch {
  int reference = -1;         ///< index of the reference mode
  int other = -1;             ///< index of the matched mode of the other model, −1 when absent
  double mac = 0.0;           ///< MAC of the match; when absent, the best MAC found [-]
  int best_other = -1;        ///< the other mode with the best MAC (even when below the threshold)
  double reference_hz = 0.0;  ///< f of the reference mode [Hz]
  double other_hz = 0.0;      ///< f of the matched mode [Hz] (NaN when absent)
  /// (f_other − f_ref)/f_ref [-]; 0 when both are rigid-body (zero) modes; NaN when absent or
  /// when only the reference is zero.
  double relative_difference = 0.0;
};

/// @brief The matching of all reference modes against another model's modes.
struct ModeMatching {
  std::vector<ModeMatch> matches;  ///< one per reference mode, in reference order
  std::vector<int> extra;          ///< other-model modes matched to no reference mode
  int num_matched = 0;             ///< reference modes with a match
  /// max |relative_difference| over the matched modes with a non-zero reference frequency [-].
  double max_abs_relative_difference = 0.0;
};

/// @brief Options of MatchModesByMac and CalcModalAssuranceMatrix.
struct ModeMatchingOptions {
  double mac_threshold = 0.8;  ///< least MAC of a match, in (0, 1]
  /// Frequencies within this relative gap form a cluster compared as a subspace, in [0, 0.1):
  /// near-repeated modes (e.g. the tilt modes of a pair of identical gears on identical bearings)
  /// mix arbitrarily between two models that differ slightly.
  double cluster_rel_tol = 1e-3;
  /// False (with the field, value and bound in `why`) on an invalid value.
  bool IsValid(std::string* why) const;
};

/// @brief The (m_ref × m_other) MAC matrix of two sets of shapes (see the @file; clusters of
/// near-repeated frequencies compared as subspaces).
/// @param[in] reference modes with shapes (n × m_ref) and multiplicity_groups.
/// @param[in] other modes with shapes (n × m_other).
/// @param[in] mass M (n × n) [kg, kg·m, kg·m²], the mass both shapes are normalized with.
/// @throws InvalidInput on invalid options, when a result has no shapes or the sizes disagree.
MatrixX CalcModalAssuranceMatrix(const ModalResult& reference, const ModalResult& other,
                                 const SparseMatrix& mass, const ModeMatchingOptions& options = {});

/// @brief Matches every reference mode with a mode of `other` (see the @file).
/// @throws InvalidInput on invalid options or as CalcModalAssuranceMatrix.
ModeMatching MatchModesByMac(const ModalResult& reference, const ModalResult& other,
                             const SparseMatrix& mass, const ModeMatchingOptions& options = {});

}  // namespace geardyn
