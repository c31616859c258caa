// The full dense linear HB system in the real layout (MakeLinearHbSystem, the kDirect path),
// option validation and names (harmonic_balance.hpp).
#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/system/system_harmonics.hpp"
#include "hb_internal.hpp"

namespace geardyn {

using internal::Complex;

const char* ToString(HbMethod method) {
  switch (method) {
    case HbMethod::kAuto:
      return "auto";
    case HbMethod::kDecoupled:
      return "decoupled";
    case HbMethod::kCondensed:
      return "condensed";
    case HbMethod::kDirect:
      return "direct";
  }
  return "unknown";
}

bool HbOptions::IsValid(std::string* why) const {
  std::ostringstream msg;
  if (harmonics < 0) {
    msg << "HbOptions::harmonics: must be >= 0 (0 = from the tolerance), got " << harmonics;
  } else if (harmonics == 0 && !(std::isfinite(tolerance) && tolerance > 0.0)) {
    msg << "HbOptions::tolerance: must be finite and > 0, got " << tolerance;
  } else if (harmonics > kMaxHbHarmonics) {
    msg << "HbOptions::harmonics: must be <= " << kMaxHbHarmonics << ", got " << harmonics
        << " (the condensed coupling of one mesh in one forcing class alone would take "
           "(2(2H+1))^2 x 16 B = "
        << std::setprecision(3) << 64.0 * std::pow(2.0 * harmonics + 1.0, 2) / 1e9 << " GB)";
  } else if (min_harmonics < 1) {
    msg << "HbOptions::min_harmonics: must be >= 1, got " << min_harmonics;
  } else if (max_harmonics < min_harmonics) {
    msg << "HbOptions::max_harmonics: must be >= min_harmonics = " << min_harmonics << ", got "
        << max_harmonics;
  } else if (max_harmonics > kMaxHbHarmonics) {
    msg << "HbOptions::max_harmonics: must be <= " << kMaxHbHarmonics << ", got " << max_harmonics;
  } else if (time_samples < 0) {
    msg << "HbOptions::time_samples: must be >= 0 (0 = automatic), got " << time_samples;
  } else if (time_samples > 0 && time_samples <= 2 * (harmonics > 0 ? harmonics : max_harmonics)) {
    msg << "HbOptions::time_samples: must exceed 2H = "
        << 2 * (harmonics > 0 ? harmonics : max_harmonics) << " (sampling theorem), got "
        << time_samples;
  }
  if (why != nullptr) *why = msg.str();
  return msg.str().empty();
}

LinearHbSystem MakeLinearHbSystem(const SystemModel& model, int harmonics,
                                  double mesh_frequency_hz) {
  GEARDYN_THROW_UNLESS(harmonics >= 1, "harmonics: must be >= 1, got " << harmonics);
  GEARDYN_THROW_UNLESS(std::isfinite(mesh_frequency_hz) && mesh_frequency_hz > 0.0,
                       "mesh_frequency_hz: must be finite and > 0, got " << mesh_frequency_hz);
  internal::CheckLinearHbModel(model);
  const int H = harmonics;
  const int n = model.num_dofs();
  const long unknowns = static_cast<long>(n) * (2 * H + 1);
  GEARDYN_THROW_UNLESS(unknowns <= 6000, "MakeLinearHbSystem: (2H+1)·n = "
                                             << unknowns
                                             << " unknowns exceed the dense limit 6000; use "
                                                "the condensed solver");
  const double omega =
      2.0 * std::numbers::pi * mesh_frequency_hz / static_cast<double>(model.period_meshes());
  const SystemHarmonics sh = ExpandSystemHarmonics(model, 2 * H);
  const MatrixX M = model.DenseMass();
  const internal::RigidModes rigid = internal::ComputeRigidModes(sh.stiffness[0].real());

  LinearHbSystem sys;
  sys.matrix = MatrixX::Zero(unknowns, unknowns);
  for (int k = 0; k <= H; ++k) {
    for (int j = -H; j <= H; ++j) {
      const int m = k - j;
      if (std::abs(m) > 2 * H) continue;
      const MatrixXc& Km = sh.stiffness[std::abs(m)];
      const MatrixXc& Cm = sh.damping[std::abs(m)];
      // Harmonic k of K(θ)q + C(θ)q̇: K_{k−j} Q_j + C_{k−j} (ijΩ) Q_j.
      MatrixXc B = m >= 0 ? MatrixXc(Km + Complex(0.0, j * omega) * Cm)
                          : MatrixXc(Km.conjugate() + Complex(0.0, j * omega) * Cm.conjugate());
      if (j == k) B += Complex(-(k * omega) * (k * omega), 0.0) * M.cast<internal::Complex>();
      if (k == 0 && j == 0 && rigid.count() > 0)
        B += (rigid.U * rigid.U.transpose()).cast<Complex>();
      internal::AddRealBlock(n, k, j, B, &sys.matrix);
    }
  }
  std::vector<VectorXc> F(H + 1);
  for (int k = 0; k <= H; ++k) F[k] = sh.load[k];
  internal::BalanceMeanLoad(rigid, &F[0]);
  sys.rhs = internal::ToRealLayout(F);
  return sys;
}

}  // namespace geardyn
