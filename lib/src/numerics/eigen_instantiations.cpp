// The one explicit instantiation definition of each Eigen decomposition that
// geardyn/numerics/eigen_instantiations.hpp declares extern (a build-speed device: see there).
#include "geardyn/numerics/eigen_instantiations.hpp"

#define GEARDYN_EIGEN_TEMPLATE(...) template __VA_ARGS__;
GEARDYN_EIGEN_INSTANTIATIONS(GEARDYN_EIGEN_TEMPLATE)
#undef GEARDYN_EIGEN_TEMPLATE
