// Reading one [[load]] table: a constant external torque on a gear, or a force along a rack.
#include "scene/element_names.hpp"
#include "scene/section_readers.hpp"
#include "scene/toml_fields.hpp"

namespace geardyn::internal {

TorqueLoadDef ReadLoad(const ErrorContext& ctx, const toml::table& t, std::size_t index,
                       const Scene& scene) {
  TorqueLoadDef ld;
  CheckElementKeys(ctx, t, "load", index, {"name", "body", "torque", "force"});
  ld.name = ReadElementName(ctx, t, "load", index);
  const Fields f(ctx, t, "load." + ld.name);
  ld.body = ReadGearName(f, "body", "name of the loaded [[gear]]", scene);
  if (scene.gear(ld.body).blank.kind == GearKind::kRack) {
    if (f.Find("torque") != nullptr) {
      f.Fail("torque", "'" + ld.body +
                           "' is a rack: it takes a force along its direction of travel, "
                           "force = ... [N], not a torque");
    }
    ld.force = f.ReqNumber("force", "force in N along the rack's direction of travel").value;
  } else {
    if (f.Find("force") != nullptr) {
      f.Fail("force", "only a rack takes a force; '" + ld.body + "' is a gear: give torque [N m]");
    }
    ld.torque = f.ReqNumber("torque", "torque in N m about the common +z axis").value;
  }
  return ld;
}

}  // namespace geardyn::internal
