// The transmission-error model of a scene mesh (mesh_transmission_error.hpp).
#include "geardyn/models/scene/mesh_transmission_error.hpp"

#include "geardyn/models/scene/scene.hpp"
#include "scene/mesh_model_reader.hpp"

namespace geardyn {

std::optional<TransmissionErrorModel> MakeMeshTransmissionErrorModel(
    const Scene& scene, const MeshDef& mesh, const ContactLineModel& lines) {
  const MeshModelDef& model = mesh.model;
  ToothErrors errors = model.errors;
  if (errors.pinion_teeth == 0) errors.pinion_teeth = scene.gear(mesh.pinion).blank.teeth;
  if (errors.gear_teeth == 0) errors.gear_teeth = scene.gear(mesh.gear).blank.teeth;
  if (!internal::HasUnloadedSeparation(model.modifications, errors)) return std::nullopt;
  return TransmissionErrorModel(lines, model.modifications, errors);
}

}  // namespace geardyn
