// From a scene mesh to its MeshCore: ISO line load, drive sign, stiffness source, transmission
// error channels and the requested level, all from one MeshCoreSource (spec 01 §4, §5).
#include "geardyn/models/scene/mesh_model.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "geardyn/common/check.hpp"
#include "geardyn/models/contact/contact_mesh_core.hpp"
#include "geardyn/models/mesh/transmission_error.hpp"
#include "geardyn/models/scene/mesh_transmission_error.hpp"
#include "geardyn/models/scene/planetary.hpp"
#include "geardyn/models/scene/scene.hpp"
#include "scene/mesh_model_reader.hpp"
#include "scene/speed_ratios.hpp"

namespace geardyn {
namespace {

// Gears reachable from `start` through the meshes other than `excluded` and the bearings that
// tie two gears torsionally (stiffness(5, 5) > 0), a carrier to its planets and a shaft to its
// gears: the elements that carry torque.
std::set<std::string, std::less<>> ReachableWithout(const Scene& scene, const std::string& start,
                                                    const std::string& excluded) {
  std::set<std::string, std::less<>> seen = {start};
  std::deque<std::string> queue = {start};
  const auto visit = [&](const std::string& a, const std::string& b, const std::string& from) {
    if (from == a && seen.insert(b).second) queue.push_back(b);
    if (from == b && seen.insert(a).second) queue.push_back(a);
  };
  while (!queue.empty()) {
    const std::string from = queue.front();
    queue.pop_front();
    for (const MeshDef& m : scene.meshes) {
      if (m.name != excluded) visit(m.pinion, m.gear, from);
    }
    for (const BearingDef& b : scene.bearings) {
      if (!b.other.empty() && b.stiffness(5, 5) > 0.0) visit(b.body, b.other, from);
    }
    // Power also passes where CalcSpeedRatios ties speeds without a torsional bearing: a carrier
    // drives its planets through their (radial) bearings, a shaft turns with its gears.
    for (const PlanetaryDef& set : scene.planetaries) {
      for (const std::string& planet : set.planets) visit(set.carrier, planet, from);
    }
    for (const ShaftDef& shaft : scene.shafts) {
      for (const ShaftGearDef& g : shaft.gears) visit(shaft.name, g.gear, from);
    }
  }
  return seen;
}

// The level's core on the user's channels.
LinearMeshCore MakeUserCore(const MeshDef& mesh) {
  const MeshModelDef& model = mesh.model;
  const std::string prefix = "mesh." + mesh.name;
  GEARDYN_THROW_UNLESS(model.level != MeshModelLevel::kNonlinearSlices,
                       prefix << ".parameters: user parameters cannot make the slice model (the "
                                 "slices need the contact lines)");
  GEARDYN_THROW_UNLESS(!model.stiffness_per_length &&
                           !internal::HasUnloadedSeparation(model.modifications, model.errors),
                       prefix << ".parameters: user parameters replace the contact-line model; "
                                 "stiffness_per_length, modifications and errors are not used "
                                 "with them");
  const UserMeshParameters& p = *model.parameters;
  const LinearMeshCore core(CalcMeshCoreLevel(model.level), p.stiffness,
                            0.5 * mesh.geometry.face_width, p.transmission_error, model.damping);
  if (model.level == MeshModelLevel::kMeanLti) return MakeMeanLinearMeshCore(core);
  // five_dof: B–S's scalar transmission error (Eq. 42), the user's te_zeta dropped.
  if (model.level == MeshModelLevel::kFiveDof) return MakeScalarTransmissionErrorCore(core);
  return core;
}

// The coefficient keys the scene gave that cannot change the core (they were silently ignored):
// fourier_terms / fourier_tolerance when coefficient_form = "auto" stores the exact steps of a
// spur mesh (MakeMeshCoefficient, MakeSliceMeshCore: the steps come before any series), and
// table_samples when nothing is sampled: no transmission error (its table is the only sampled
// coefficient of the Fourier, auto and piecewise-constant forms) and neither the "table" form of
// a linear mesh nor the sampled stiffness of slices that are not exact steps.
std::vector<std::string> UnusedCoefficientKeys(const MeshModelDef& model,
                                               const ContactLineModel& lines) {
  std::vector<std::string> out;
  const MeshCoefficientForm form = model.core_options.coefficient.form;
  const bool slices = model.level == MeshModelLevel::kNonlinearSlices;
  const bool exact_steps =
      lines.is_piecewise_constant() &&
      (form == MeshCoefficientForm::kAuto || form == MeshCoefficientForm::kPiecewiseConstant);
  if (model.fourier_keys_given && form == MeshCoefficientForm::kAuto && exact_steps) {
    out.push_back(
        "fourier_terms/fourier_tolerance have no effect: coefficient_form = \"auto\" stores the "
        "exact stiffness steps of this spur mesh, not a Fourier series (give coefficient_form = "
        "\"fourier\" for a truncated series)");
  }
  const bool te = internal::HasUnloadedSeparation(model.modifications, model.errors);
  const bool sampled = te || (slices ? !exact_steps : form == MeshCoefficientForm::kTable);
  if (model.table_samples_given && !sampled) {
    out.push_back(
        std::string("table_samples has no effect: the mesh has no transmission error (no tooth "
                    "modifications or errors) and coefficient_form = \"") +
        (form == MeshCoefficientForm::kAuto      ? "auto"
         : form == MeshCoefficientForm::kFourier ? "fourier"
                                                 : "piecewise_constant") +
        "\" does not sample the stiffness" + (slices ? " of these slices (exact steps)" : "") +
        " (give coefficient_form = \"table\" for a sampled stiffness)");
  }
  return out;
}

// ε(θ) from the modifications and errors on the contact lines (none when they are all zero): a
// table (or its Fourier series) over the hunting period, bounded by kMaxTransmissionErrorSamples
// samples; or, for a runout on a linear level without pitch deviations (RunoutForm), the table of
// ε without the runout (mesh-periodic) plus the runout's two lines.
struct MeshTransmissionError {
  std::optional<Coefficient> coefficient;
  TransmissionErrorSidebands sidebands;
};

std::optional<Coefficient> TransmissionErrorCoefficient(const TransmissionErrorModel& te,
                                                        const MeshDef& mesh) {
  const MeshCoefficientOptions& options = mesh.model.core_options.coefficient;
  const std::int64_t period = te.period_meshes();
  if (options.form == MeshCoefficientForm::kFourier) {
    const int per_mesh =
        options.num_terms > 0 ? options.num_terms : (options.num_samples + 1) / 2 - 1;
    const std::int64_t terms = static_cast<std::int64_t>(per_mesh) * period;
    GEARDYN_THROW_UNLESS(terms <= std::numeric_limits<int>::max(),
                         "fourier_terms: " << per_mesh << " harmonics per mesh cycle over "
                                           << period << " cycles is too many");
    return MakeTransmissionErrorFourierCoefficient(te, static_cast<int>(terms),
                                                   options.num_samples);
  }
  return MakeTransmissionErrorTableCoefficient(te, options.num_samples);
}

MeshTransmissionError MakeTransmissionError(const Scene& scene, const MeshDef& mesh,
                                            const ContactLineModel& lines, RunoutForm runout) {
  const std::optional<TransmissionErrorModel> te =
      MakeMeshTransmissionErrorModel(scene, mesh, lines);
  if (!te) return {};
  const MeshCoefficientOptions& options = mesh.model.core_options.coefficient;
  const std::int64_t period = te->period_meshes();
  const std::int64_t samples = static_cast<std::int64_t>(options.num_samples) * period;
  const ToothErrors& errors = te->separation().errors();
  const auto nonzero = [](const std::vector<double>& v) {
    return std::any_of(v.begin(), v.end(), [](double x) { return x != 0.0; });
  };
  const bool sidebands_apply = mesh.model.level != MeshModelLevel::kNonlinearSlices &&
                               (errors.pinion_runout > 0.0 || errors.gear_runout > 0.0) &&
                               !nonzero(errors.pinion_pitch_deviations) &&
                               !nonzero(errors.gear_pitch_deviations) && errors.pinion_teeth >= 2 &&
                               errors.gear_teeth >= 2;
  if (sidebands_apply &&
      (runout == RunoutForm::kSidebands ||
       (runout == RunoutForm::kAuto && samples > kMaxTransmissionErrorSamples))) {
    MeshTransmissionError out;
    out.sidebands = MakeRunoutSidebands(te->separation());
    if (te->separation().has_flank_modifications()) {
      const TransmissionErrorModel mesh_periodic(te->contact_lines(),
                                                 te->separation().modifications());
      out.coefficient = TransmissionErrorCoefficient(mesh_periodic, mesh);
    }
    return out;
  }
  GEARDYN_THROW_UNLESS(
      samples <= kMaxTransmissionErrorSamples,
      "mesh."
          << mesh.name << ".errors: the transmission error repeats over a hunting period of "
          << period << " mesh cycles (lcm of " << errors.pinion_teeth << " and "
          << errors.gear_teeth << " teeth); its table of " << options.num_samples
          << " samples per cycle would hold " << samples << " samples ("
          << static_cast<double>(samples) * 16.0 / 1e9
          << " GB, several times more in a harmonic balance), above the limit "
          << kMaxTransmissionErrorSamples
          << ". modes, floquet and stability-chart do not need it, and mesh samples it "
             "directly (linear models); the linear hb takes a runout alone (no pitch errors) on "
             "a linear level as sidebands; otherwise lower table_samples, or give tooth "
             "counts with a common factor, or leave out the pitch errors and runout");
  return {TransmissionErrorCoefficient(*te, mesh), {}};
}

// True when the slice model's lumping changes the answer: tooth pairs in contact at once (in one
// σ band) with different unloaded separations. The slice core has one spring per σ band over all
// the pairs in it, with their stiffness-weighted mean separation e_s = ε_η − σ_s ε_ζ
// (MakeSliceMeshCore), i.e. Σ_j k_j (v − ē)⁺ instead of Σ_j k_j (v − e_j)⁺: exact while every
// pair stays loaded (v ≥ max e_j), wrong where one pair should separate (docs/design.md, "The
// slice model's tip relief"). Profile relief and pitch deviations differ between the pairs; lead
// modifications only on a helical pair (the lines in one σ band cross it at different y); a
// runout is uniform on all lines.
bool SeparationDiffersBetweenPairs(const MeshModelDef& model, const ContactLineModel& lines) {
  const ToothModifications& m = model.modifications;
  const auto nonzero = [](const std::vector<double>& v) {
    return std::any_of(v.begin(), v.end(), [](double x) { return x != 0.0; });
  };
  const bool lead =
      (m.lead_crowning != 0.0 || m.lead_slope != 0.0) && lines.zone().base_helix_angle != 0.0;
  return m.pinion_tip_relief.is_active() || m.gear_tip_relief.is_active() ||
         m.pinion_root_relief.is_active() || m.gear_root_relief.is_active() || lead ||
         nonzero(model.errors.pinion_pitch_deviations) ||
         nonzero(model.errors.gear_pitch_deviations);
}

}  // namespace

std::optional<double> MeshLineLoad(const Scene& scene, const MeshDef& mesh) {
  const GearPairGeometry& g = mesh.geometry;
  const std::string& body = scene.operating_point.body;
  if (const auto set = scene.FindPlanetaryMesh(mesh.name)) {
    // Planetary: every sun and ring mesh carries F_t = |T_s| / (N r_s), T_s the sun torque of
    // the operating point's torque (static ratios 1 : z_r/z_s : −(1 + z_r/z_s)).
    const PlanetaryDef& p = *set->first;
    const double zr_over_zs = static_cast<double>(p.ring_teeth) / p.sun_teeth;
    double ratio = 0.0;
    if (body == p.sun) ratio = 1.0;
    if (body == p.ring) ratio = zr_over_zs;
    if (body == p.carrier) ratio = -(1.0 + zr_over_zs);
    if (ratio == 0.0 || scene.operating_point.torque == 0.0) return std::nullopt;
    const double sun_radius = p.sun_meshes[set->second] == mesh.name
                                  ? g.pinion.reference_radius
                                  : g.transverse_module * p.sun_teeth / 2.0;
    return std::abs(scene.operating_point.torque / ratio) /
           (static_cast<double>(p.planets.size()) * sun_radius) / g.face_width;
  }
  double radius = 0.0;
  if (body == mesh.pinion) radius = g.pinion.reference_radius;
  if (body == mesh.gear) radius = g.gear.reference_radius;
  if (radius <= 0.0 || scene.operating_point.torque == 0.0) return std::nullopt;
  return std::abs(scene.operating_point.torque) / radius / g.face_width;
}

int MeshDriveSign(const Scene& scene, const MeshDef& mesh, std::vector<std::string>* warnings) {
  const OperatingPointDef& op = scene.operating_point;
  const auto fallback = [&](const std::string& why) {
    if (warnings != nullptr) {
      warnings->push_back("mesh." + mesh.name + ": drive sign +1 assumed (" + why + ")");
    }
    return 1;
  };
  // Planetary meshes: the set's rule (planetary.hpp): s = s_s for the sun meshes, −s_s for the
  // ring meshes (whose pinion, the planet, reacts the sun mesh).
  if (const auto set = scene.FindPlanetaryMesh(mesh.name)) {
    const int sun_sign = PlanetarySunDriveSign(scene, *set->first, warnings);
    return set->first->sun_meshes[set->second] == mesh.name ? sun_sign : -sun_sign;
  }
  if (op.torque == 0.0) return fallback("the operating-point torque is 0: no loaded flank");
  const auto reach = ReachableWithout(scene, op.body, mesh.name);
  const bool pinion_side = reach.contains(mesh.pinion);
  const bool gear_side = reach.contains(mesh.gear);
  if (pinion_side && gear_side) {
    return fallback(
        "the mesh is in a closed loop joining both its sides to the operating-point "
        "gear '" +
        op.body + "': the power through it is not known");
  }
  if (!pinion_side && !gear_side) {
    return fallback("not connected to the operating-point gear '" + op.body + "'");
  }
  const internal::SpeedRatios ratios = internal::CalcSpeedRatios(scene, op.body);
  const auto it = ratios.ratio.find(mesh.pinion);
  GEARDYN_DEMAND(it != ratios.ratio.end() && it->second != 0.0);
  // T_p = ±T_r Ω_r / Ω_p: the torque the pinion transmits (power T_r Ω_r, + from the pinion side).
  const double pinion_torque = (pinion_side ? 1.0 : -1.0) * op.torque / it->second;
  return pinion_torque > 0.0 ? 1 : -1;
}

BuiltMeshCore BuildMeshCore(const Scene& scene, const MeshDef& mesh, bool transmission_error,
                            RunoutForm runout) {
  const MeshModelDef& model = mesh.model;
  std::vector<std::string> warnings;
  for (const std::string& w : mesh.geometry.warnings)
    warnings.push_back("mesh." + mesh.name + ": " + w);
  const int drive_sign = MeshDriveSign(scene, mesh, &warnings);
  // The tooth-contact core needs the placed frame (BuildSceneSystem, time-domain analyses).
  GEARDYN_THROW_UNLESS(model.level != MeshModelLevel::kContact,
                       "mesh." << mesh.name
                               << ".model: \"contact\" (tooth contact with tooth bodies) is "
                                  "integrated in time only; for this use run the mesh with --set "
                                  "mesh."
                               << mesh.name
                               << ".model=slices (contact loss, backlash) or =blankenship_singh "
                                  "(the linear LTV model)");
  if (model.parameters) {
    return {MakeUserCore(mesh), std::nullopt, drive_sign, std::move(warnings)};
  }

  MeshStiffnessSource stiffness = IsoStiffnessSource{};
  if (model.stiffness_per_length) {
    stiffness = StiffnessPerUnitLength{*model.stiffness_per_length};
  } else {
    std::get<IsoStiffnessSource>(stiffness).options.line_load = MeshLineLoad(scene, mesh);
  }
  MeshCoreSource source = MakeMeshCoreSource(mesh.geometry, stiffness, drive_sign);
  for (const std::string& w : source.warnings) warnings.push_back("mesh." + mesh.name + ": " + w);
  source.damping = model.damping;
  if (transmission_error) {
    MeshTransmissionError te = MakeTransmissionError(scene, mesh, source.contact_lines, runout);
    source.transmission_error = std::move(te.coefficient);
    source.transmission_error_sidebands = std::move(te.sidebands);
    if (model.level == MeshModelLevel::kNonlinearSlices &&
        SeparationDiffersBetweenPairs(model, source.contact_lines)) {
      warnings.push_back(
          "mesh." + mesh.name +
          ": model = \"slices\" gives the tooth pairs in contact at once one separation per "
          "face band (their stiffness-weighted mean, the linear-limit transmission error): "
          "relief, pitch deviations (or lead modifications of a helical pair) that should unload "
          "one pair while another carries the load keep both loaded, so the STE, K(theta) and "
          "contact loss are exact only while the separation differences stay below the tooth "
          "deflection (use model = \"contact\" for deeper relief)");
    }
  }

  MeshCoreOptions options = model.core_options;
  options.level = model.level;
  for (const std::string& w : UnusedCoefficientKeys(model, source.contact_lines)) {
    warnings.push_back("mesh." + mesh.name + ": " + w);
  }
  MeshCore core = MakeMeshCore(source, options);
  return {std::move(core), std::move(source.contact_lines), drive_sign, std::move(warnings)};
}

std::shared_ptr<const NonlinearMeshCore> BuildContactMeshCore(const Scene& scene,
                                                              const MeshDef& mesh,
                                                              const MeshFrame& frame) {
  const std::string prefix = "mesh." + mesh.name;
  try {
    const ContactMeshDef def = mesh.model.contact.value_or(ContactMeshDef{});
    auto core = std::make_shared<const ContactMeshCore>(mesh.geometry, frame, def,
                                                        mesh.model.modifications);
    const ToothSet* sets[2] = {&core->pinion_teeth(), &core->gear_teeth()};
    const std::string* names[2] = {&mesh.pinion, &mesh.gear};
    for (int k = 0; k < 2; ++k) {
      for (const GearDef& g : scene.gears) {
        if (g.name == *names[k] && g.mass && g.inertia) {
          CheckTrunkInertia(*sets[k], *g.mass, *g.inertia, "gear." + g.name);
        }
      }
    }
    return core;
  } catch (const InvalidInput& e) {
    throw InvalidInput(prefix + ".contact: " + e.what());
  }
}

}  // namespace geardyn
