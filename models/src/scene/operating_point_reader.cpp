// Reading the [operating_point] table: reference gear, speed and mean torque.
#include "geardyn/common/units.hpp"
#include "scene/element_names.hpp"
#include "scene/section_readers.hpp"
#include "scene/toml_fields.hpp"

namespace geardyn::internal {

OperatingPointDef ReadOperatingPoint(const ErrorContext& ctx, const toml::table& root,
                                     const Scene& scene) {
  const toml::node* n = root.get("operating_point");
  if (n == nullptr) {
    ctx.Fail(nullptr, "operating_point",
             "missing (required: an [operating_point] table with speed_rpm and torque)");
  }
  const toml::table* t = n->as_table();
  if (t == nullptr) {
    ctx.Fail(n, "operating_point", "must be a table ([operating_point]), got " + Describe(*n));
  }
  const Fields f(ctx, *t, "operating_point");
  f.CheckKnown({"body", "speed_rpm", "torque"});
  OperatingPointDef op;
  if (auto body = f.OptString("body")) {
    op.body = *body;
    if (GearByName(f, "body", op.body, scene).blank.kind == GearKind::kRack) {
      f.Fail("body", "'" + op.body +
                         "' is a rack: it translates and has no speed in rpm; give the operating "
                         "point on its pinion");
    }
  } else {
    op.body = scene.meshes.front().pinion;
  }
  const Number speed = f.ReqNumber("speed_rpm", "speed of the reference gear in rpm, >= 0");
  f.NonNegative("speed_rpm", speed);
  op.speed = RpmToRadPerSec(speed.value);
  op.torque = f.ReqNumber("torque", "mean torque on the reference gear in N m").value;
  return op;
}

}  // namespace geardyn::internal
