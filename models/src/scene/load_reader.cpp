// Reading one [[load]] table: a constant external torque on a gear.
#include "scene/element_names.hpp"
#include "scene/section_readers.hpp"
#include "scene/toml_fields.hpp"

namespace geardyn::internal {

TorqueLoadDef ReadLoad(const ErrorContext& ctx, const toml::table& t, std::size_t index,
                       const Scene& scene) {
  TorqueLoadDef ld;
  CheckElementKeys(ctx, t, "load", index, {"name", "body", "torque"});
  ld.name = ReadElementName(ctx, t, "load", index);
  const Fields f(ctx, t, "load." + ld.name);
  ld.body = ReadGearName(f, "body", "name of the loaded [[gear]]", scene);
  ld.torque = f.ReqNumber("torque", "torque in N m about the common +z axis").value;
  return ld;
}

}  // namespace geardyn::internal
