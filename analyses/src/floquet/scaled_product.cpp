// ScaledMatrix: long monodromy products without overflow (spec 02: "multiply in a stable way").
#include <cmath>

#include "floquet/floquet_internal.hpp"

namespace geardyn::internal {

void ScaledMatrix::Normalize() {
  const double s = matrix.cwiseAbs().maxCoeff();
  if (s > 0.0 && std::isfinite(s)) {
    matrix /= s;
    log_scale += std::log(s);
  }
}

ScaledMatrix ScaledPower(const ScaledMatrix& base, std::int64_t power, long* products) {
  // Binary powering: result = base^power, each product normalized (the log-scales add).
  ScaledMatrix result{MatrixX::Identity(base.matrix.rows(), base.matrix.cols()), 0.0};
  ScaledMatrix square = base;
  square.Normalize();
  bool first = true;
  while (power > 0) {
    if (power & 1) {
      if (first) {
        result = square;
        first = false;
      } else {
        result.matrix = square.matrix * result.matrix;
        result.log_scale += square.log_scale;
        result.Normalize();
        ++*products;
      }
    }
    power >>= 1;
    if (power > 0) {
      square.matrix = square.matrix * square.matrix;
      square.log_scale *= 2.0;
      square.Normalize();
      ++*products;
    }
  }
  return result;
}

}  // namespace geardyn::internal
