#include "geardyn/numerics/fftw_planner.hpp"

namespace geardyn {

std::mutex& FftwPlannerMutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace geardyn
