#include "mesh_core_values.hpp"

#include "geardyn/common/check.hpp"
#include "geardyn/common/overloaded.hpp"

namespace geardyn::internal {

MeshCoreValues EvalMeshCoreValues(const MeshCore& core, double c_m, SliceMeshWorkspace* slice_ws,
                                  double phase, int want) {
  MeshCoreValues out;
  std::visit(Overloaded{
                 [&](const LinearMeshCore& linear) {
                   if (want & kWantStiffness) out.stiffness = EvalStiffnessCore(linear, phase);
                   if (want & kWantDamping) out.damping = EvalDampingCore(linear, phase, c_m);
                   if ((want & kWantLoad) && linear.has_transmission_error()) {
                     out.load = EvalTransmissionErrorLoad(linear, phase);
                   }
                 },
                 [&](const SliceMeshCore& slice) {
                   if (!(want & (kWantStiffness | kWantDamping))) return;
                   GEARDYN_DEMAND(slice_ws != nullptr);
                   const Vector3 c = EvalSliceChannels(slice, *slice_ws, phase);
                   Matrix2 k2;
                   k2 << c(0), -c(1), -c(1), c(2);
                   out.stiffness = k2;
                   if ((want & kWantDamping) && k2(0, 0) > 0.0) out.damping = (c_m / k2(0, 0)) * k2;
                 },
                 [&](const std::shared_ptr<const NonlinearMeshCore>&) {},
             },
             core);
  return out;
}

}  // namespace geardyn::internal
