#include "geardyn/overlay_match.hpp"

#include <cmath>
#include <cstdio>

#include "geardyn/analyses/time_response.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/models/scene/scene.hpp"

namespace geardyn::app {
namespace {

// Samples per mesh cycle of the matching rolls (as kim_qfb_sweeps.py's --quasi-static).
constexpr int kMatchSamples = 64;
// Trial stiffness per length of the first slice roll [N/m²] (ISO's c_γα ≈ 2e10 N/m²).
constexpr double kTrialStiffnessPerLength = 1e10;

// θ-means of mesh k's quasi-static roll.
struct Means {
  double stiffness = 0.0, force = 0.0, contacts = 0.0;
};

Means MeanOf(const QuasiStaticResult& r, int k, const std::string& what) {
  GEARDYN_THROW_UNLESS(r.summary.ok(),
                       "--overlay-hb: matching the slice model: the quasi-static "
                       "roll of the "
                           << what << " failed: " << r.summary.message);
  const QuasiStaticMesh& m = r.meshes.at(static_cast<std::size_t>(k));
  Means out;
  out.stiffness = m.stiffness.row(0).mean();
  out.force = m.force_pair.row(0).mean();
  out.contacts = m.contacts.cast<double>().mean();
  GEARDYN_THROW_UNLESS(out.stiffness > 0.0, "--overlay-hb: matching the slice model: the "
                                                << what << "'s mean stiffness of mesh " << m.name
                                                << " is " << out.stiffness << " N/m (no contact)");
  return out;
}

QuasiStaticResult Roll(const SystemModel& model) {
  QuasiStaticOptions o;
  o.samples_per_mesh = kMatchSamples;
  o.sampling = QuasiStaticSampling::kMeshCycle;
  o.check_next_cycle = false;
  return SimulateQuasiStatic(model, o);
}

std::string Number(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.9g", v);
  return text;
}

}  // namespace

std::vector<SliceMatch> MatchSlicesToContact(const SystemModel& contact_model, const Scene& scene,
                                             const SliceModelBuilder& build_slices,
                                             std::vector<std::string>* warnings) {
  std::vector<SliceMatch> matches;
  const QuasiStaticResult contact = Roll(contact_model);
  std::vector<int> index;  // model mesh index of each match
  for (int k = 0; k < contact_model.num_meshes(); ++k) {
    const SystemMesh& mesh = contact_model.meshes()[static_cast<std::size_t>(k)];
    if (!std::holds_alternative<std::shared_ptr<const NonlinearMeshCore>>(mesh.core)) continue;
    const Means c = MeanOf(contact, k, "contact model");
    const MeshDef* def = nullptr;
    for (const MeshDef& d : scene.meshes) {
      if (d.name == mesh.name) def = &d;
    }
    GEARDYN_THROW_UNLESS(def != nullptr, "--overlay-hb: mesh " << mesh.name << " not in the scene");
    const ContactMeshDef contact_def = def->model.contact.value_or(ContactMeshDef{});
    ContactLaw law = contact_def.law;  // the law of one contact (one face slice)
    if (law.kind != ContactLawKind::kLine) {
      law.stiffness /= contact_def.face_slices;
      law.damping /= contact_def.face_slices;
    }
    SliceMatch m;
    m.mesh = mesh.name;
    m.contact_mean_stiffness = c.stiffness;
    m.mean_force = c.force;
    m.mean_contacts = c.contacts;
    const double pair_force = std::abs(c.force) / std::max(c.contacts, 1.0);
    double indentation = std::abs(c.force) / c.stiffness;  // line law: the secant estimate
    if (law.kind == ContactLawKind::kKim) {
      indentation = std::pow(pair_force / law.stiffness, 1.0 / law.stiffness_exponent);
    } else if (law.kind == ContactLawKind::kLinear) {
      indentation = pair_force / law.stiffness;
    }
    if (law.kind == ContactLawKind::kLinear || law.damping_exponent == 1.0) {
      const double m3 = law.kind == ContactLawKind::kLinear ? 0.0 : law.indentation_exponent;
      m.damping = c.contacts * law.damping * std::pow(indentation, m3);
    } else if (warnings != nullptr) {
      warnings->push_back("--overlay-hb: mesh " + mesh.name +
                          ": the contact damping exponent m2 = " + Number(law.damping_exponent) +
                          " has no linear part; the matched slice model has no mesh damping");
    }
    matches.push_back(m);
    index.push_back(k);
  }
  // k = k₀ K̄_c / K̄_s(k₀), twice (K̄_s ∝ k while every slice is loaded).
  for (SliceMatch& m : matches) m.stiffness_per_length = kTrialStiffnessPerLength;
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<std::string> overrides;
    for (const SliceMatch& m : matches) {
      overrides.push_back("mesh." + m.mesh + ".model=slices");
      overrides.push_back("mesh." + m.mesh +
                          ".stiffness_per_length=" + Number(m.stiffness_per_length));
    }
    const QuasiStaticResult slices = Roll(build_slices(overrides));
    for (std::size_t i = 0; i < matches.size(); ++i) {
      SliceMatch& m = matches[i];
      const double ks = MeanOf(slices, index[i], "slice model").stiffness;
      m.slice_mean_stiffness = ks;
      m.stiffness_per_length *= m.contact_mean_stiffness / ks;
    }
  }
  return matches;
}

std::vector<std::string> MatchedSliceOverrides(const std::vector<SliceMatch>& matches) {
  std::vector<std::string> out;
  for (const SliceMatch& m : matches) {
    out.push_back("mesh." + m.mesh + ".model=slices");
    out.push_back("mesh." + m.mesh + ".stiffness_per_length=" + Number(m.stiffness_per_length));
    out.push_back("mesh." + m.mesh + ".damping=" + Number(m.damping));
  }
  return out;
}

}  // namespace geardyn::app
