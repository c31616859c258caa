// MakeOscillatorSystemModel: the dimensionless gear-mesh oscillator as a SystemModel
// (oscillator_system.hpp).
#include "geardyn/models/system/oscillator_system.hpp"

#include <cmath>
#include <complex>
#include <numbers>
#include <optional>

#include "geardyn/common/check.hpp"
#include "geardyn/system/coefficient.hpp"
#include "geardyn/system/mesh_core.hpp"
#include "geardyn/system/system_builder.hpp"

namespace geardyn {
namespace {

// k(1 + α cos θ) on `channels` channels (only the first non-zero): constant when α = 0.
Coefficient StiffnessCoefficient(double k, double alpha, int channels) {
  VectorX mean = VectorX::Zero(channels);
  mean(0) = k;
  if (alpha == 0.0) return ConstantCoefficient(mean);
  MatrixXc harmonics = MatrixXc::Zero(channels, 1);
  harmonics(0, 0) = 0.5 * alpha * k;  // k α cos θ = 2 Re(kα/2 e^{iθ})
  return FourierCoefficient(mean, harmonics);
}

}  // namespace

SystemModel MakeOscillatorSystemModel(const OscillatorDef& o) {
  GEARDYN_THROW_UNLESS(std::isfinite(o.zeta) && o.zeta >= 0.0,
                       "oscillator.zeta: must be finite and >= 0, got " << o.zeta);
  GEARDYN_THROW_UNLESS(std::isfinite(o.alpha) && std::abs(o.alpha) < 1.0,
                       "oscillator.alpha: must satisfy |alpha| < 1, got " << o.alpha);
  GEARDYN_THROW_UNLESS(std::isfinite(o.mean_force) && std::isfinite(o.alternating_force) &&
                           std::isfinite(o.force_phase),
                       "oscillator: non-finite mean_force "
                           << o.mean_force << ", alternating_force " << o.alternating_force
                           << " or force phase " << o.force_phase);
  GEARDYN_THROW_UNLESS(o.backlash || o.model != OscillatorModel::kSlices,
                       "oscillator.model: \"slices\" is the clearance model, but backlash = false");
  const double wn = 2.0 * std::numbers::pi * kOscillatorNaturalFrequencyHz;
  const double k = wn * wn;

  SystemBuilder b;
  const BodyIndex mass = b.AddBody("mass", Matrix6::Identity());
  const BodyIndex ground = b.AddBody("ground", Matrix6::Identity());
  Matrix6 damping = Matrix6::Zero();
  damping(0, 0) = 2.0 * o.zeta * wn;
  b.AddElement("damper", ElementKind::kSpring, {mass}, Matrix6::Zero(), damping);

  Matrix2x12 G = Matrix2x12::Zero();
  G(0, 0) = 1.0;                      // x of "mass"
  G(0, 6) = -1.0;                     // x of "ground"
  constexpr double kUnitWidth = 1.0;  // b of the core: only reported (μ), x is dimensionless
  MeshCore core = [&]() -> MeshCore {
    switch (o.model) {
      case OscillatorModel::kSlices:
        return SliceMeshCore(VectorX::Zero(1), StiffnessCoefficient(k, o.alpha, 1), kUnitWidth,
                             Coefficient(ConstantCoefficient(VectorX::Ones(1))),
                             o.back_contact ? 2.0 : kNoBackFlank);
      case OscillatorModel::kTorsional:
        return LinearMeshCore(MeshCoreLevel::kTorsional, StiffnessCoefficient(k, o.alpha, 3),
                              kUnitWidth);
      case OscillatorModel::kLti:
        break;
    }
    return LinearMeshCore(MeshCoreLevel::kTorsional, StiffnessCoefficient(k, 0.0, 3), kUnitWidth,
                          std::nullopt, MeshDamping{}, /*mean_lti=*/true);
  }();
  b.AddMesh("oscillator", mass, ground, G, std::move(core));

  Vector6 mean = Vector6::Zero();
  mean(0) = o.mean_force * k;
  b.AddTorque(mass, mean, "mean_force");
  if (o.alternating_force != 0.0) {
    Vector6c amplitude = Vector6c::Zero();
    amplitude(0) = std::polar(o.alternating_force * k, o.force_phase);
    b.AddHarmonicLoad(mass, amplitude, 1, "alternating_force");
  }
  return b.Build().Restrict({0});
}

}  // namespace geardyn
