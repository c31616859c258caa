// Defaults of the [mesh.contact] table from the gear geometry (contact_mesh_def.hpp).
#include "geardyn/models/contact/contact_mesh_def.hpp"

namespace geardyn {

const char* ToString(ContactProfile profile) {
  return profile == ContactProfile::kBiarc ? "biarc" : "involute";
}

BushingJoint ResolveBushing(const ContactMeshDef& def, const GearGeometry& gear) {
  const ToothSection s = CalcToothSection(gear);
  const double root_area = s.root_thickness * gear.face_width;  // A_f = s_f b
  const double shear_modulus = def.young_modulus / (2.0 * (1.0 + def.poisson));
  BushingJoint j;
  j.radial_stiffness =
      def.bushing_radial_stiffness.value_or(def.young_modulus * root_area / s.height);
  j.tangential_stiffness = def.bushing_tangential_stiffness.value_or(
      kShearCorrection * shear_modulus * root_area / s.height);
  j.rotational_stiffness = def.bending_stiffness;
  j.rotational_damping = def.bending_damping;
  const double tau =
      def.bending_stiffness > 0.0 ? def.bending_damping / def.bending_stiffness : 0.0;
  j.radial_damping = def.bushing_radial_damping.value_or(tau * j.radial_stiffness);
  j.tangential_damping = def.bushing_tangential_damping.value_or(tau * j.tangential_stiffness);
  return j;
}

ToothSet ResolveToothSet(const ContactMeshDef& def, const GearGeometry& gear) {
  ToothSet set;
  set.type = def.teeth;
  set.teeth = gear.teeth;
  if (def.teeth == ToothBodyType::kRigid) return set;
  const ToothSection s = CalcToothSection(gear);
  set.inertia = CalcToothInertia(s, def.density, gear.face_width);
  if (def.tooth_mass) {
    set.inertia.mass = *def.tooth_mass;
    set.inertia.centroid_inertia = *def.tooth_inertia;
  }
  return set;
}

}  // namespace geardyn
