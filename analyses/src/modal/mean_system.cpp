#include "geardyn/analyses/mean_system.hpp"

#include <utility>

#include "modal_internal.hpp"

namespace geardyn {

MeanSystemMatrices AssembleMeanSystemMatrices(const SystemModel& model) {
  MeanSystemMatrices out;
  internal::MeanSystem sys = internal::AssembleMeanSystem(model, &out.warnings);
  out.mass = std::move(sys.M);
  out.damping = std::move(sys.C);
  out.stiffness = std::move(sys.K);
  return out;
}

}  // namespace geardyn
