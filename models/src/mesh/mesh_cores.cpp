/// @file
/// @brief Builders of the mesh cores per level (spec 01 §4, §5) from one MeshCoreSource.
#include "geardyn/models/mesh/mesh_cores.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <sstream>
#include <utility>

#include "geardyn/common/check.hpp"
#include "geardyn/common/overloaded.hpp"
#include "geardyn/common/units.hpp"
#include "geardyn/models/mesh/mesh_jacobian.hpp"

namespace geardyn {
namespace {

/// Columns equal to this relative tolerance (of the largest entry) make a constant coefficient:
/// the same criterion as MakeMeshCoefficient's kAuto (1e-13 relative).
constexpr double kConstantTol = 1e-13;

/// The coefficient A·f (channels mapped by a constant matrix A, rows = new channels): exact for
/// every representation because all of them are linear in their values.
Coefficient MapChannels(const Coefficient& coef, const MatrixX& A) {
  return std::visit(
      Overloaded{
          [&](const ConstantCoefficient& c) -> Coefficient {
            return ConstantCoefficient(A * c.values(), c.period_meshes());
          },
          [&](const PiecewiseConstantCoefficient& c) -> Coefficient {
            return PiecewiseConstantCoefficient(c.breakpoints(), A * c.values(), c.period_meshes());
          },
          [&](const FourierCoefficient& c) -> Coefficient {
            const MatrixXc Ac = A.cast<std::complex<double>>();
            return FourierCoefficient(A * c.mean(), Ac * c.harmonics(), c.period_meshes());
          },
          [&](const TableCoefficient& c) -> Coefficient {
            return TableCoefficient(A * c.samples(), c.period_meshes());
          },
      },
      coef);
}

/// True when all columns of m are equal to kConstantTol of its largest entry.
bool ColumnsConstant(const MatrixX& m) {
  const double scale = m.cwiseAbs().maxCoeff();
  for (Eigen::Index k = 1; k < m.cols(); ++k) {
    if ((m.col(k) - m.col(0)).cwiseAbs().maxCoeff() > kConstantTol * scale) return false;
  }
  return true;
}

/// The band edges of slice s: equal bands over SigmaRange(); the two outer bands extend one
/// range width further so that no round-off sliver of a line escapes (Σ k_s = K to round-off).
void SliceBand(const Vector2& range, int num_slices, int s, double* lo, double* hi) {
  const double width = range[1] - range[0];
  const double step = width / num_slices;
  *lo = s == 0 ? range[0] - width : range[0] + s * step;
  *hi = s == num_slices - 1 ? range[1] + width : range[0] + (s + 1) * step;
}

void CheckNumSlices(int num_slices) {
  GEARDYN_THROW_UNLESS(num_slices >= 1, "num_slices: must be >= 1, got " << num_slices);
}

}  // namespace

// ---------------------------------------------------------------------------- sources

StiffnessProfile ResolveStiffnessProfile(const MeshStiffnessSource& source,
                                         const GearPairGeometry& geometry, const ZoneOfAction& zone,
                                         std::vector<std::string>* warnings) {
  return std::visit(
      Overloaded{
          [&](const IsoStiffnessSource& iso_source) {
            const IsoMeshStiffness iso = CalcIsoMeshStiffness(geometry, iso_source.options);
            if (warnings != nullptr) {
              warnings->insert(warnings->end(), iso.warnings.begin(), iso.warnings.end());
            }
            // c_γα is the mean mesh stiffness per unit face width: K̄ = c_γα·B. The contact-line
            // model gives K̄ = k·L̄ for a constant k, with L̄ the mean contact-line length; take
            // L̄ as the exact period mean of the model's own L(θ) (k = 1 gives K ≡ L).
            const ContactLineModel unit(zone, StiffnessProfile::Constant(1.0));
            const double mean_length = MakeFourierMeshCoefficient(unit, 0).mean()[0];
            GEARDYN_DEMAND(mean_length > 0.0);
            return StiffnessProfile::Constant(iso.mesh_alpha * zone.face_width / mean_length);
          },
          [&](const StiffnessPerUnitLength& given) {
            GEARDYN_THROW_UNLESS(std::isfinite(given.k) && given.k >= 0.0,
                                 "stiffness.k: must be finite and >= 0 [N/m^2], got " << given.k);
            return StiffnessProfile::Constant(given.k);
          },
          [&](const StiffnessProfile& profile) { return profile; },
      },
      source);
}

MeshCoreSource MakeMeshCoreSource(const GearPairGeometry& geometry,
                                  const MeshStiffnessSource& stiffness, int drive_sign) {
  const ZoneOfAction zone = MakeZoneOfAction(geometry, drive_sign);
  std::vector<std::string> warnings;
  StiffnessProfile profile = ResolveStiffnessProfile(stiffness, geometry, zone, &warnings);
  MeshCoreSource source{ContactLineModel(zone, std::move(profile)),
                        std::nullopt,
                        MeshDamping{},
                        geometry.backlash_normal,
                        std::move(warnings),
                        {}};
  return source;
}

// ---------------------------------------------------------------------------- levels

const char* ToString(MeshModelLevel level) {
  switch (level) {
    case MeshModelLevel::kNonlinearSlices:
      return "slices";
    case MeshModelLevel::kBlankenshipSingh:
      return "blankenship_singh";
    case MeshModelLevel::kBsProjected:
      return "bs_projected";
    case MeshModelLevel::kFiveDof:
      return "five_dof";
    case MeshModelLevel::kCoupling4Dof:
      return "coupling_4dof";
    case MeshModelLevel::kMeanLti:
      return "lti";
    case MeshModelLevel::kTorsional:
      return "torsional";
    case MeshModelLevel::kContact:
      return "contact";
  }
  return "unknown";
}

std::optional<MeshModelLevel> ParseMeshModelLevel(std::string_view name) {
  for (MeshModelLevel level :
       {MeshModelLevel::kNonlinearSlices, MeshModelLevel::kBlankenshipSingh,
        MeshModelLevel::kBsProjected, MeshModelLevel::kFiveDof, MeshModelLevel::kCoupling4Dof,
        MeshModelLevel::kMeanLti, MeshModelLevel::kTorsional, MeshModelLevel::kContact}) {
    if (name == ToString(level)) return level;
  }
  return std::nullopt;
}

MeshCoreLevel CalcMeshCoreLevel(MeshModelLevel level) {
  switch (level) {
    case MeshModelLevel::kCoupling4Dof:
      return MeshCoreLevel::kCoupling4Dof;
    case MeshModelLevel::kTorsional:
      return MeshCoreLevel::kTorsional;
    case MeshModelLevel::kBlankenshipSingh:
    case MeshModelLevel::kBsProjected:
    case MeshModelLevel::kFiveDof:
    case MeshModelLevel::kMeanLti:
    case MeshModelLevel::kNonlinearSlices:
    case MeshModelLevel::kContact:
      break;
  }
  return MeshCoreLevel::kBlankenshipSingh;
}

Matrix2x12 CalcModelLevelJacobian(MeshModelLevel level, const MeshFrame& frame,
                                  double half_face_width) {
  switch (level) {
    case MeshModelLevel::kBsProjected:
      return CalcBsProjectedJacobian(frame, half_face_width);
    case MeshModelLevel::kTorsional:
      return CalcLevelJacobian(MeshCoreLevel::kTorsional, CalcMeshJacobian(frame));
    case MeshModelLevel::kBlankenshipSingh:
    case MeshModelLevel::kFiveDof:
    case MeshModelLevel::kCoupling4Dof:
    case MeshModelLevel::kMeanLti:
    case MeshModelLevel::kNonlinearSlices:
    case MeshModelLevel::kContact:
      break;
  }
  return CalcMeshJacobian(frame);
}

LinearMeshCore MakeScalarTransmissionErrorCore(const LinearMeshCore& core) {
  if (!core.has_transmission_error()) return core;
  std::optional<Coefficient> te;
  if (core.transmission_error()) {
    // Keep channel 0 (ε_η), zero channel 1 (ε_ζ): B–S Eq. (42).
    const MatrixX keep_eta = (MatrixX(2, 2) << 1.0, 0.0, 0.0, 0.0).finished();
    te = MapChannels(*core.transmission_error(), keep_eta);
  }
  TransmissionErrorSidebands sidebands = core.sidebands();
  if (!sidebands.empty()) sidebands.coefficients.row(1).setZero();
  return LinearMeshCore(core.level(), core.stiffness(), core.half_face_width(), std::move(te),
                        core.damping(), core.is_mean_lti(), std::move(sidebands));
}

bool SliceCoefficientOptions::IsValid(std::string* why) const {
  std::ostringstream msg;
  if (num_samples < 1) {
    msg << "num_samples: must be >= 1, got " << num_samples;
  } else if (num_terms < 0 || num_terms > num_samples / 2) {
    msg << "num_terms: must be in [0, num_samples/2 = " << num_samples / 2 << "], got "
        << num_terms;
  } else {
    return true;
  }
  if (why != nullptr) *why = msg.str();
  return false;
}

LinearMeshCore MakeLinearMeshCore(const MeshCoreSource& source, MeshModelLevel level,
                                  const MeshCoefficientOptions& options) {
  switch (level) {
    case MeshModelLevel::kNonlinearSlices:
      GEARDYN_THROW_UNLESS(false,
                           "level: 'slices' is not a linear level; use MakeSliceMeshCore "
                           "or MakeMeshCore");
      break;
    case MeshModelLevel::kContact:
      GEARDYN_THROW_UNLESS(false,
                           "level: 'contact' is not a linear level (a tooth-contact "
                           "NonlinearMeshCore, built by BuildMeshCore)");
      break;
    case MeshModelLevel::kBlankenshipSingh:
    case MeshModelLevel::kBsProjected:
    case MeshModelLevel::kFiveDof:
    case MeshModelLevel::kMeanLti:
    case MeshModelLevel::kCoupling4Dof:
    case MeshModelLevel::kTorsional:
      break;
  }
  const MeshCoreLevel core_level = CalcMeshCoreLevel(level);
  LinearMeshCore core(core_level, MakeMeshCoefficient(source.contact_lines, options),
                      source.contact_lines.half_face_width(), source.transmission_error,
                      source.damping, /*mean_lti=*/false, source.transmission_error_sidebands);
  if (level == MeshModelLevel::kMeanLti) return MakeMeanLinearMeshCore(core);
  if (level == MeshModelLevel::kFiveDof) return MakeScalarTransmissionErrorCore(core);
  return core;
}

// ---------------------------------------------------------------------------- slices

VectorX CalcSliceSigma(const ContactLineModel& model, int num_slices) {
  CheckNumSlices(num_slices);
  const Vector2 range = model.SigmaRange();
  const double step = (range[1] - range[0]) / num_slices;
  VectorX sigma(num_slices);
  for (int s = 0; s < num_slices; ++s) sigma[s] = range[0] + (s + 0.5) * step;
  return sigma;
}

void CalcSliceStiffness(const ContactLineModel& model, int num_slices, double theta,
                        Eigen::Ref<VectorX> out) {
  CheckNumSlices(num_slices);
  GEARDYN_CHECK_SIZE(out.size(), num_slices, "out");
  const Vector2 range = model.SigmaRange();
  for (int s = 0; s < num_slices; ++s) {
    double lo = 0.0, hi = 0.0;
    SliceBand(range, num_slices, s, &lo, &hi);
    out[s] = model.CalcIntegrals(theta, lo, hi).stiffness;
  }
}

SliceMeshCore MakeSliceMeshCore(const MeshCoreSource& source, int num_slices,
                                const SliceCoefficientOptions& options) {
  CheckNumSlices(num_slices);
  std::string why;
  GEARDYN_THROW_UNLESS(options.IsValid(&why), "options." << why);
  GEARDYN_THROW_UNLESS(source.transmission_error_sidebands.empty(),
                       "transmission_error_sidebands: the slice model needs ε as a table of its "
                       "separations over the hunting period, not as sidebands");
  const ContactLineModel& model = source.contact_lines;
  const VectorX sigma = CalcSliceSigma(model, num_slices);

  const bool exact_steps = model.is_piecewise_constant();
  GEARDYN_THROW_UNLESS(options.form != MeshCoefficientForm::kPiecewiseConstant || exact_steps,
                       "options.form: the slice stiffness is piecewise constant only for a spur "
                       "zone (base_helix_angle = "
                           << model.zone().base_helix_angle
                           << ") with a piecewise-constant stiffness profile");
  std::optional<Coefficient> stiffness;
  const bool use_steps = options.form == MeshCoefficientForm::kPiecewiseConstant ||
                         (options.form == MeshCoefficientForm::kAuto && exact_steps);
  if (use_steps) {
    // Spur: each line spans the whole face, so every band changes exactly where the whole mesh
    // does (a line entering or leaving, a profile knot): the model's breakpoints.
    std::vector<double> breaks = model.Breakpoints();
    if (breaks.empty()) breaks.push_back(0.0);
    const auto count = static_cast<Eigen::Index>(breaks.size());
    VectorX starts(count);
    MatrixX values(num_slices, count);
    for (Eigen::Index k = 0; k < count; ++k) {
      const double a = breaks[static_cast<size_t>(k)];
      const double b = k + 1 < count ? breaks[static_cast<size_t>(k + 1)] : breaks[0] + 2.0 * kPi;
      starts[k] = a;
      CalcSliceStiffness(model, num_slices, 0.5 * (a + b), values.col(k));
    }
    if (options.form == MeshCoefficientForm::kAuto && ColumnsConstant(values)) {
      stiffness = ConstantCoefficient(values.col(0));
    } else {
      stiffness = PiecewiseConstantCoefficient(std::move(starts), std::move(values));
    }
  } else {
    MatrixX samples(num_slices, options.num_samples);
    for (int i = 0; i < options.num_samples; ++i) {
      CalcSliceStiffness(model, num_slices, 2.0 * kPi * i / options.num_samples, samples.col(i));
    }
    if (options.form == MeshCoefficientForm::kAuto && ColumnsConstant(samples)) {
      stiffness = ConstantCoefficient(samples.col(0));
    } else if (options.form == MeshCoefficientForm::kFourier) {
      const int terms = options.num_terms > 0 ? options.num_terms : options.num_samples / 2;
      stiffness = ToFourier(TableCoefficient(std::move(samples)), terms);
    } else {
      stiffness = TableCoefficient(std::move(samples));
    }
  }

  std::optional<Coefficient> separation;
  if (source.transmission_error) {
    GEARDYN_THROW_UNLESS(NumChannels(*source.transmission_error) == 2,
                         "transmission_error: has " << NumChannels(*source.transmission_error)
                                                    << " channels, expected 2 (eps_eta, "
                                                       "eps_zeta)");
    // e_s = ε_η − σ_s ε_ζ: the rigid separation field whose linear-limit load is K2 ε.
    MatrixX map(num_slices, 2);
    map.col(0).setOnes();
    map.col(1) = -sigma;
    separation = MapChannels(*source.transmission_error, map);
  }
  return SliceMeshCore(sigma, std::move(*stiffness), model.half_face_width(), std::move(separation),
                       source.backlash, source.damping);
}

MeshCore MakeMeshCore(const MeshCoreSource& source, const MeshCoreOptions& options) {
  if (options.level == MeshModelLevel::kNonlinearSlices) {
    return MakeSliceMeshCore(source, options.num_slices, options.slices);
  }
  return MakeLinearMeshCore(source, options.level, options.coefficient);
}

}  // namespace geardyn
