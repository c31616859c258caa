/// @file
/// @brief The common period of a system whose meshes run at different frequencies (a two-stage
/// train, issue 18): the smallest whole number q of mesh cycles of the system phase θ (the phase
/// of ratio 1) after which every mesh's coefficients repeat.
///
/// Mesh k has the phase θ_k = r_k θ + φ_k (SystemMesh::MeshPhase) and coefficients of period
/// 2π P_k in θ_k (PeriodMeshes of its core). The system is 2πq-periodic in θ iff r_k q / P_k is
/// a whole number for every k. With r = 7/40 (a planetary stage behind a parallel stage whose
/// tooth counts give that ratio) q = 40 P; for an irrational ratio no q exists, and a ratio whose
/// denominator exceeds the bound is treated alike (its period is too long to be of use: the
/// response is then quasi-periodic for every practical purpose).
#pragma once

#include <cstdint>

#include "geardyn/system/system_model.hpp"

namespace geardyn {

/// @brief Common period of the system (see @file) [mesh cycles of θ].
/// @param[in] model any model; all ratios 1 give model.period_meshes() (0 above the bound: a
///   single-frequency caller uses model.period_meshes() directly).
/// @param[in] max_period_meshes search bound ≥ 1 [mesh cycles].
/// @param[in] cycle_tolerance r_k q / P_k counts as whole when it is within this many cycles of
///   a whole number [-], in [0, 1e-3]: the phase slip of mesh k over one period. Ratios from
///   tooth counts are exact to ~1e-16 relative; an irrational r has convergents p/q with
///   |r q − p| ≈ 1/(c q), so with the defaults (1e-6, 10⁵) neither √2 nor the golden ratio has a
///   period (their first fits are at q ≈ 3.5·10⁵ and 4.5·10⁵).
/// @return q ≥ 1, a multiple of model.period_meshes(); 0 when no q ≤ max_period_meshes exists.
/// @throws InvalidInput on max_period_meshes < 1 or a cycle_tolerance outside [0, 1e-3].
std::int64_t FindCommonPeriodMeshes(const SystemModel& model,
                                    std::int64_t max_period_meshes = 100'000,
                                    double cycle_tolerance = 1e-6);

/// True when some mesh's phase ratio differs from 1 by more than 1e-12 (the test of
/// CheckSingleMeshFrequency).
bool HasSeveralMeshFrequencies(const SystemModel& model);

}  // namespace geardyn
