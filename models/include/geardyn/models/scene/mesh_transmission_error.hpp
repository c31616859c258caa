/// @file
/// @brief The transmission-error model of one scene mesh (its contact lines, flank modifications
/// and tooth errors, spec 01 §4), evaluated pointwise: what `geardyn mesh` samples and the bound
/// on the ε table that BuildMeshCore stores over the hunting period.
///
/// **Why pointwise.** With tooth errors ε repeats only over the hunting period P = lcm(z_1, z_2)
/// mesh cycles (P = 988 027 for 997/991 teeth), and the core stores it as a table of
/// num_samples·P samples. Analyses of the homogeneous problem (modes, Floquet, stability charts)
/// build no ε at all (SceneSystemOptions::transmission_error = false); a report of ε over a few
/// mesh cycles evaluates the exact TransmissionErrorModel at its own samples instead.
#pragma once

#include <cstdint>
#include <optional>

#include "geardyn/models/mesh/contact_lines.hpp"
#include "geardyn/models/mesh/transmission_error.hpp"

namespace geardyn {

struct Scene;    // scene.hpp
struct MeshDef;  // scene.hpp

/// Largest ε table BuildMeshCore builds over a hunting period [samples] (2 channels of 8 B:
/// 0.27 GB; the linear HB's expansion holds 8 channels at twice the resolution, ≈ 2 GB).
inline constexpr std::int64_t kMaxTransmissionErrorSamples = std::int64_t{1} << 24;

/// @brief The exact transmission-error model of a contact-line mesh of the scene, or none when
/// the mesh has no modification and no tooth error (ε ≡ 0).
/// @param[in] scene a validated scene (tooth counts of the gears fill errors.*_teeth when 0).
/// @param[in] mesh one of its meshes, without user parameters.
/// @param[in] lines the mesh's contact-line model (BuiltMeshCore::contact_lines).
/// @throws InvalidInput as TransmissionErrorModel (fields "modifications.*", "errors.*").
std::optional<TransmissionErrorModel> MakeMeshTransmissionErrorModel(const Scene& scene,
                                                                     const MeshDef& mesh,
                                                                     const ContactLineModel& lines);

}  // namespace geardyn
