/// @file
/// @brief The slice model matched to a tooth-contact mesh for `geardyn simulate --overlay-hb`
/// (the nonlinear HB curve drawn against a contact-model sweep), as examples/kim_qfb/
/// kim_qfb_sweeps.py does by hand:
/// * **stiffness per length** k [N/m²] such that the slice model's quasi-static mean mesh
///   stiffness equals the contact model's, K̄_s(k) = K̄_c (both from SimulateQuasiStatic,
///   kMeshCycle; the contact law and tooth joints linearised at the load). K̄_s is proportional to
///   k while every slice in the zone of action is loaded, so k = k₀ K̄_c / K̄_s(k₀), repeated once
///   from the result (spur pair: k = K̄_c / (b ε_α), b the face width);
/// * **mesh damping** c_m [N·s/m] = n̄ c_c δ̄^{m₃}: the contact law's damping (Kim Eq. 12,
///   f_d = c δ̇^{m₂} δ^{m₃}, linearised in δ̇ for m₂ = 1) at the mean contact load F̄/n̄, summed over
///   the n̄ contacts in action on average (n̄ the mean num_contacts of the quasi-static roll, = ε_α
///   for a spur pair with one face slice), with c_c and k_c the law of one contact (one face
///   slice: k/N, c/N; the line law as given) and δ̄ from k_c δ̄^{m₁} = F̄/n̄ (the line law, which has
///   no closed-form inverse here: δ̄ = F̄/K̄_c, used only when m₃ ≠ 0). The contact damper acts in
///   series with the tooth joints (type A/B), so c_m is an upper bound of its effect there; the
///   joints' own damping c_b is not carried over (the slice model has no tooth bodies). For
///   m₂ ≠ 1 the damping has no linear part and c_m = 0 (a warning says so).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "geardyn/system/system_model.hpp"

namespace geardyn {
struct Scene;
}

namespace geardyn::app {

/// The match of one contact mesh.
struct SliceMatch {
  std::string mesh;                   ///< the mesh's name
  double contact_mean_stiffness = 0;  ///< K̄_c [N/m]
  double mean_force = 0;              ///< F̄_η [N]
  double mean_contacts = 0;           ///< n̄ [-]
  double stiffness_per_length = 0;    ///< k [N/m²]
  double slice_mean_stiffness = 0;    ///< K̄_s at the previous iterate, scaled to k [N/m]
  double damping = 0;                 ///< c_m [N·s/m]
};

/// Builds the slice model of the scene with these extra `--set` overrides (e.g.
/// "mesh.NAME.model=slices").
using SliceModelBuilder = std::function<SystemModel(const std::vector<std::string>& overrides)>;

/// @brief The matched slice parameters of every contact (NonlinearMeshCore) mesh of `scene`.
/// @param[in] contact_model the built model of `scene` (contact meshes allowed).
/// @param[in] scene the scene it was built from (the [mesh.contact] law of each mesh).
/// @param[in] build_slices builds the slice model with extra overrides.
/// @param[out] warnings notes on the match (m₂ ≠ 1).
/// @throws InvalidInput when a quasi-static roll fails (its status and message) or a mean
///   stiffness is not positive (no contact).
std::vector<SliceMatch> MatchSlicesToContact(const SystemModel& contact_model, const Scene& scene,
                                             const SliceModelBuilder& build_slices,
                                             std::vector<std::string>* warnings);

/// The `--set` overrides of the matched slice model: per mesh model = "slices",
/// stiffness_per_length = k, damping = c_m.
std::vector<std::string> MatchedSliceOverrides(const std::vector<SliceMatch>& matches);

}  // namespace geardyn::app
