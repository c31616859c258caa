#include "geardyn/models/system/scene_system.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <deque>
#include <numbers>
#include <optional>
#include <sstream>

#include "geardyn/common/check.hpp"
#include "geardyn/models/elements/bearing.hpp"
#include "geardyn/models/elements/rigid_body.hpp"
#include "geardyn/models/elements/shaft_beam.hpp"
#include "geardyn/models/mesh/mesh_frame.hpp"
#include "geardyn/models/mesh/mesh_jacobian.hpp"
#include "geardyn/models/mesh/mesh_preload_stiffness.hpp"
#include "geardyn/models/scene/mesh_model.hpp"
#include "geardyn/models/scene/planetary.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/oscillator_system.hpp"
#include "geardyn/numerics/rigid_modes.hpp"
#include "geardyn/system/static_deflection.hpp"
#include "geardyn/system/system_builder.hpp"
#include "geardyn/system/system_damping.hpp"
#include "geardyn/system/workspace.hpp"

namespace geardyn {
namespace {

constexpr double kLoopTol = 1e-9;  // relative centre-distance mismatch accepted in a closed loop

// The rigid-body modes N of the unloaded model stay exact zero-energy motions of the loaded one
// (a loaded train with balanced torques still turns freely): the preload's ΔK = K0' − K0 is
// replaced by Pᵀ ΔK P, P = I − N (Nᵀ M N)⁻¹ Nᵀ M, the M-orthogonal projector off N. ΔK is first
// order in the preload and the flexible modes φ (M-orthogonal to N, P φ = φ) keep their
// first-order shifts φᵀ ΔK φ; what the projection removes, ΔK N, would be balanced by terms of
// second order (the rotation of the static deflections with the train), which the first-order
// tangent leaves out and whose absence turns the free rotation of a planetary train into a
// spurious divergence (λ ≈ −14 rad²/s² on planetary-lin-parker). Returns dim N when the
// projection changed ΔK, 0 otherwise.
int KeepRigidBodyModes(const SystemModel& plain, SystemModel* loaded) {
  SystemWorkspace ws(plain, StorageKind::kDense);
  const RigidBodyModes rigid = ComputeRigidBodyModes(AssembleMeanStiffness(plain, ws));
  if (!rigid.ok || rigid.count() == 0) return 0;
  const MatrixX M = plain.DenseMass();
  const MatrixX dK = loaded->DenseConstantStiffness() - plain.DenseConstantStiffness();
  const MatrixX& N = rigid.modes;
  const double scale = dK.cwiseAbs().maxCoeff();
  if (scale == 0.0 || (dK * N).cwiseAbs().maxCoeff() <= 1e-14 * scale * N.cwiseAbs().maxCoeff()) {
    return 0;
  }
  const MatrixX MN = M * N;
  const MatrixX P =
      MatrixX::Identity(M.rows(), M.cols()) - N * (N.transpose() * MN).ldlt().solve(MN.transpose());
  MatrixX correction = P.transpose() * dK * P - dK;
  correction = 0.5 * (correction + correction.transpose());
  // Entries of round-off size (between decoupled blocks) are dropped so the blocks stay.
  const SparseMatrix sparse = correction.sparseView(1.0, 1e-13 * scale);
  *loaded = loaded->WithAddedStiffness(sparse);
  return rigid.count();
}

int GearIndex(const Scene& scene, const std::string& name) {
  for (std::size_t g = 0; g < scene.gears.size(); ++g) {
    if (scene.gears[g].name == name) return static_cast<int>(g);
  }
  GEARDYN_THROW_UNLESS(false, "gear '" << name << "': unknown");
  return -1;
}

// A body's mass or inertia, which the scene may omit (geometry and mesh stiffness do not use
// them): its absence is an error of the scene, at the body's table, naming what needs it.
double RequireMassProperty(const Scene& scene, const GearDef& gear, const char* field,
                           const std::optional<double>& value, const std::string& analysis) {
  if (value) return *value;
  const std::string key = (gear.key.empty() ? "gear." + gear.name : gear.key) + "." + field;
  throw SceneError(scene.source, gear.line, key,
                   "required by " + analysis + " (mass matrix); the scene does not give it");
}

// A body of the placement walk: gear g is g, shaft s is num_gears + s.
struct Endpoint {
  int node = 0;                      // walk node
  Vector3 offset = Vector3::Zero();  // station along +z from the node's centre [m]
  std::optional<double> station;     // on a shaft
};

Endpoint FindEndpoint(const Scene& scene, const std::string& name,
                      const std::optional<double>& station) {
  for (std::size_t s = 0; s < scene.shafts.size(); ++s) {
    if (scene.shafts[s].name == name) {
      return {static_cast<int>(scene.gears.size() + s), Vector3(0.0, 0.0, station.value_or(0.0)),
              station};
    }
  }
  return {GearIndex(scene, name), Vector3::Zero(), std::nullopt};
}

// Index of the node of `shaft` nearest `station`.
int NearestNode(const ShaftDef& shaft, double station) {
  int best = 0;
  for (int k = 1; k < static_cast<int>(shaft.nodes.size()); ++k) {
    if (std::abs(shaft.nodes[k] - station) < std::abs(shaft.nodes[best] - station)) best = k;
  }
  return best;
}

}  // namespace

bool SceneSystemOptions::IsValid(std::string* why) const {
  std::ostringstream os;
  if (!std::isfinite(line_of_centres_angle)) {
    os << "line_of_centres_angle: must be finite, got " << line_of_centres_angle;
  } else if (!origin.allFinite()) {
    os << "origin: must be finite";
  } else {
    for (const auto& [name, angle] : mesh_angles) {
      if (!std::isfinite(angle)) {
        os << "mesh_angles." << name << ": must be finite, got " << angle;
        break;
      }
    }
  }
  if (os.str().empty()) return true;
  if (why != nullptr) *why = os.str();
  return false;
}

SceneSystem BuildSceneSystem(const Scene& scene, const SceneSystemOptions& options) {
  std::string why;
  GEARDYN_THROW_UNLESS(options.IsValid(&why), why);
  if (scene.oscillator) {  // an oscillator scene (oscillator_system.hpp)
    GEARDYN_THROW_UNLESS(!options.mesh_preload,
                         scene.source << ": the mesh preload (--loaded) needs the meshes' lines of "
                                         "action, and an oscillator scene has no gear geometry");
    SceneSystem out;
    out.model = MakeOscillatorSystemModel(*scene.oscillator);
    out.warnings.push_back(kOscillatorUnitsNote);
    return out;
  }
  GEARDYN_THROW_UNLESS(!scene.gears.empty(), "scene: no gears");
  for (const MeshDef& m : scene.meshes) {
    GEARDYN_THROW_UNLESS(
        options.allow_contact_meshes || m.model.level != MeshModelLevel::kContact,
        "mesh." << m.name << ".model: \"contact\" is the time-domain tooth-contact model "
                << "(geardyn simulate); " << options.analysis
                << " needs a linear or slice mesh core: run it with --set mesh." << m.name
                << ".model=slices (contact loss, backlash) or =blankenship_singh (the linear LTV "
                   "model)");
  }
  const int num_gears = static_cast<int>(scene.gears.size());
  const int num_meshes = static_cast<int>(scene.meshes.size());
  for (const auto& [name, angle] : options.mesh_angles) {
    bool found = false;
    for (const MeshDef& m : scene.meshes) found = found || m.name == name;
    GEARDYN_THROW_UNLESS(found, "mesh_angles." << name << ": no mesh of that name");
    GEARDYN_THROW_UNLESS(!scene.FindPlanetaryMesh(name),
                         "mesh_angles." << name
                                        << ": a planetary mesh; its line of centres follows "
                                           "from its planet's angle");
  }

  GEARDYN_THROW_UNLESS(!(options.planar || scene.planar) || scene.shafts.empty(),
                       "planar: a scene with shafts cannot be planar (shaft bending needs the "
                       "tilts θx, θy that the planar model holds fixed)");
  SceneSystem out;
  // ---- Placement: BFS from the operating point's body over meshes and two-body bearings.
  std::string root_name = scene.operating_point.body;
  if (root_name.empty()) root_name = num_meshes > 0 ? scene.meshes[0].pinion : scene.gears[0].name;
  const int root = GearIndex(scene, root_name);
  const int num_shafts = static_cast<int>(scene.shafts.size());
  // Centres of the gears, then of the shafts (station 0), by walk node.
  std::vector<std::optional<Vector3>> centre(num_gears + num_shafts);
  std::vector<double> gamma(num_meshes, 0.0);
  std::vector<bool> mesh_done(num_meshes, false);
  centre[root] = options.origin;
  std::deque<int> queue{root};
  int walk = 0;
  auto place = [&](int g, const Vector3& c) {
    centre[g] = c;
    queue.push_back(g);
  };
  // A planetary set is placed as a whole when any member is reached: central members coaxial,
  // planet n at a_w (cos ψ_n, sin ψ_n) from the set's centre.
  auto place_planetary = [&](int g) {
    for (const PlanetaryDef& set : scene.planetaries) {
      std::optional<Vector3> c0;
      const std::string& name = scene.gears[g].name;
      if (name == set.sun || name == set.ring || name == set.carrier) c0 = *centre[g];
      for (std::size_t n = 0; n < set.planets.size(); ++n) {
        if (name == set.planets[n]) {
          const double psi = set.planet_angles[n];
          c0 = *centre[g] - set.center_distance * Vector3(std::cos(psi), std::sin(psi), 0.0);
        }
      }
      if (!c0) continue;
      for (const std::string* member : {&set.sun, &set.ring, &set.carrier}) {
        const int m = GearIndex(scene, *member);
        if (!centre[m]) place(m, *c0);
      }
      for (std::size_t n = 0; n < set.planets.size(); ++n) {
        const int m = GearIndex(scene, set.planets[n]);
        const double psi = set.planet_angles[n];
        if (!centre[m]) {
          place(m, *c0 + set.center_distance * Vector3(std::cos(psi), std::sin(psi), 0.0));
        }
      }
    }
  };
  // Gears on a shaft are coaxial with it, at their stations along +z.
  auto place_shaft = [&](int node) {
    for (int s = 0; s < num_shafts; ++s) {
      const ShaftDef& shaft = scene.shafts[s];
      const int sn = num_gears + s;
      for (const ShaftGearDef& sg : shaft.gears) {
        const int gi = GearIndex(scene, sg.gear);
        const Vector3 z(0.0, 0.0, sg.station);
        if (node == gi && !centre[sn]) place(sn, *centre[gi] - z);
        if (node == sn && !centre[gi]) place(gi, *centre[sn] + z);
      }
    }
  };
  while (!queue.empty()) {
    const int g = queue.front();
    queue.pop_front();
    place_shaft(g);
    if (g >= num_gears) {
      for (const BearingDef& b : scene.bearings) {  // couplings from a shaft
        if (b.other.empty()) continue;
        const Endpoint a = FindEndpoint(scene, b.body, b.station);
        const Endpoint o = FindEndpoint(scene, b.other, b.other_station);
        if (a.node == g && !centre[o.node]) place(o.node, *centre[g] + a.offset - o.offset);
        if (o.node == g && !centre[a.node]) place(a.node, *centre[g] + o.offset - a.offset);
      }
      continue;
    }
    place_planetary(g);
    for (int k = 0; k < num_meshes; ++k) {
      if (mesh_done[k]) continue;
      const MeshDef& m = scene.meshes[k];
      const int p = GearIndex(scene, m.pinion);
      const int w = GearIndex(scene, m.gear);
      if (p != g && w != g) continue;
      mesh_done[k] = true;
      // A rack's reference point is the pitch point, r_1 from the pinion axis (mesh_frame.hpp).
      const double a_w =
          m.geometry.rack ? m.geometry.pinion.operating_pitch_radius : m.geometry.center_distance;
      if (centre[p] && centre[w]) {  // closed loop: γ from the placed centres
        const Vector3 d = *centre[w] - *centre[p];
        const double dist = std::hypot(d.x(), d.y());
        GEARDYN_THROW_UNLESS(std::abs(d.z()) <= kLoopTol * a_w,
                             "mesh '" << m.name << "': its gears are placed " << d.z()
                                      << " m apart axially by their shafts and the other "
                                         "meshes (meshing gears share one transverse plane)");
        GEARDYN_THROW_UNLESS(std::abs(dist - a_w) <= kLoopTol * a_w,
                             "mesh '" << m.name << "': its gears are placed " << dist
                                      << " m apart by the other meshes, but its centre distance "
                                         "is "
                                      << a_w << " m (closed loop)");
        gamma[k] = std::atan2(d.y(), d.x());
        continue;
      }
      const auto it = options.mesh_angles.find(m.name);
      // A rack lies below its pinion (−y) and runs along +x unless its angle is given.
      gamma[k] = it != options.mesh_angles.end() ? it->second
                 : m.geometry.rack
                     ? -0.5 * std::numbers::pi
                     : options.line_of_centres_angle + (walk % 2) * std::numbers::pi / 2.0;
      if (!m.geometry.rack || it != options.mesh_angles.end()) ++walk;
      const Vector3 step(a_w * std::cos(gamma[k]), a_w * std::sin(gamma[k]), 0.0);
      if (centre[p]) {
        place(w, *centre[p] + step);
      } else {
        place(p, *centre[w] - step);
      }
    }
    for (const BearingDef& b : scene.bearings) {
      if (b.other.empty()) continue;
      const Endpoint a = FindEndpoint(scene, b.body, b.station);
      const Endpoint o = FindEndpoint(scene, b.other, b.other_station);
      if (a.node == g && !centre[o.node]) place(o.node, *centre[g] + a.offset - o.offset);
      if (o.node == g && !centre[a.node]) place(a.node, *centre[g] + o.offset - a.offset);
    }
  }
  for (int node = 0; node < num_gears + num_shafts; ++node) {
    if (!centre[node]) {  // connected to nothing: at the origin, with the gears of its shaft
      place(node, options.origin);
      while (!queue.empty()) {
        place_shaft(queue.front());
        queue.pop_front();
      }
    }
  }
  for (int g = 0; g < num_gears; ++g) out.centres.push_back(*centre[g]);

  // ---- Bodies.
  SystemBuilder builder;
  std::vector<BodyIndex> body(num_gears);
  for (int g = 0; g < num_gears; ++g) {
    const GearDef& gear = scene.gears[g];
    RigidBodyInertia inertia;
    inertia.mass = RequireMassProperty(scene, gear, "mass", gear.mass, options.analysis);
    inertia.polar_inertia =
        RequireMassProperty(scene, gear, "inertia", gear.inertia, options.analysis);
    inertia.diametral_inertia = gear.transverse_inertia.value_or(0.5 * inertia.polar_inertia);
    body[g] = builder.AddBody(gear.name, CalcRigidBodyMassMatrix(inertia), out.centres[g]);
  }
  for (const PlanetaryDef& set : scene.planetaries) {
    builder.SetBodyRole(body[GearIndex(scene, set.sun)], BodyRole::kSun);
    builder.SetBodyRole(body[GearIndex(scene, set.ring)], BodyRole::kRing);
    builder.SetBodyRole(body[GearIndex(scene, set.carrier)], BodyRole::kCarrier);
    for (const std::string& planet : set.planets) {
      builder.SetBodyRole(body[GearIndex(scene, planet)], BodyRole::kPlanet);
    }
  }
  // Mesh phase offsets of the planetary meshes (planetary.hpp), by mesh name.
  std::map<std::string, double> phase_offsets;
  for (const PlanetaryDef& set : scene.planetaries) {
    const int sun_sign = PlanetarySunDriveSign(scene, set);
    const PlanetaryMeshPhases phases = CalcPlanetaryMeshPhases(set, sun_sign);
    for (std::size_t n = 0; n < set.planets.size(); ++n) {
      phase_offsets[set.sun_meshes[n]] = phases.sun[n];
      phase_offsets[set.ring_meshes[n]] = phases.ring[n];
    }
  }

  // ---- Shafts: a body per node (the gear's body on a gear's node, massless otherwise) and a
  // Timoshenko element per pair of consecutive nodes.
  std::vector<std::vector<BodyIndex>> shaft_nodes(num_shafts);
  for (int s = 0; s < num_shafts; ++s) {
    const ShaftDef& shaft = scene.shafts[s];
    const Vector3 origin = *centre[num_gears + s];
    std::vector<int> gear_at(shaft.nodes.size(), -1);
    for (const ShaftGearDef& sg : shaft.gears) {
      gear_at[NearestNode(shaft, sg.station)] = GearIndex(scene, sg.gear);
    }
    for (std::size_t k = 0; k < shaft.nodes.size(); ++k) {
      shaft_nodes[s].push_back(
          gear_at[k] >= 0 ? body[gear_at[k]]
                          : builder.AddBody(shaft.name + ".n" + std::to_string(k), Matrix6::Zero(),
                                            origin + Vector3(0.0, 0.0, shaft.nodes[k])));
    }
    for (std::size_t k = 0; k + 1 < shaft.nodes.size(); ++k) {
      const ShaftSectionDef& section =
          shaft.sections[shaft.SectionAt(shaft.nodes[k], shaft.nodes[k + 1])];
      ShaftBeam beam;
      beam.node_a = origin + Vector3(0.0, 0.0, shaft.nodes[k]);
      beam.node_b = origin + Vector3(0.0, 0.0, shaft.nodes[k + 1]);
      beam.section = section.section;
      beam.material = shaft.material;
      builder.AddElement(shaft.name + ".e" + std::to_string(k), ElementKind::kShaft,
                         {shaft_nodes[s][k], shaft_nodes[s][k + 1]},
                         MatrixX(CalcShaftBeamStiffness(beam)), MatrixX(),
                         MatrixX(CalcShaftBeamMass(beam)));
    }
  }
  // The system body and its position of a bearing's end.
  auto resolve = [&](const std::string& name, const std::optional<double>& station) {
    const Endpoint e = FindEndpoint(scene, name, station);
    if (e.node < num_gears) return std::make_pair(body[e.node], out.centres[e.node]);
    const ShaftDef& shaft = scene.shafts[e.node - num_gears];
    const int k = NearestNode(shaft, *station);
    return std::make_pair(shaft_nodes[e.node - num_gears][k],
                          Vector3(*centre[e.node] + Vector3(0.0, 0.0, shaft.nodes[k])));
  };

  // ---- Bearings.
  for (const BearingDef& b : scene.bearings) {
    const auto [ba, ca] = resolve(b.body, b.station);
    if (b.other.empty()) {
      builder.AddElement(b.name, ElementKind::kBearing, {ba}, MatrixX(b.stiffness),
                         MatrixX(b.damping));
    } else {
      const auto [bo, co] = resolve(b.other, b.other_station);
      builder.AddElement(b.name, ElementKind::kBearing, {ba, bo},
                         MatrixX(CalcBearingMatrix(b.stiffness, ca, ca, co)),
                         MatrixX(CalcBearingMatrix(b.damping, ca, ca, co)));
    }
  }

  // ---- Meshes.
  double reference_frequency = 0.0;
  std::vector<MeshFrame> frames;
  for (int k = 0; k < num_meshes; ++k) {
    const MeshDef& m = scene.meshes[k];
    const int p = GearIndex(scene, m.pinion);
    const int w = GearIndex(scene, m.gear);
    const bool contact = m.model.level == MeshModelLevel::kContact;  // allowed above
    BuiltMeshCore built =
        contact ? BuiltMeshCore{std::shared_ptr<const NonlinearMeshCore>(), std::nullopt, 1, {}}
                : BuildMeshCore(scene, m, options.transmission_error, options.runout_form);
    if (contact) built.drive_sign = MeshDriveSign(scene, m, &built.warnings);
    for (std::string& warning : built.warnings) out.warnings.push_back(std::move(warning));
    const MeshFrame frame = CalcMeshFrame(m.geometry, out.centres[p], gamma[k], built.drive_sign);
    frames.push_back(frame);
    if (contact) {
      built.core = BuildContactMeshCore(scene, m, frame);
    }
    // The level's G: the exact G, its θz columns (torsional) or B–S's projected-arm G_BS = P T
    // (bs_projected, with the core's half face width b).
    const auto* linear = std::get_if<LinearMeshCore>(&built.core);
    const Matrix2x12 G = CalcModelLevelJacobian(
        m.model.level, frame,
        linear != nullptr ? linear->half_face_width() : 0.5 * m.geometry.face_width);
    double ratio = 1.0;
    try {
      const double f = scene.MeshFrequencyHz(m);
      if (k == 0) reference_frequency = f;
      if (reference_frequency > 0.0 && f > 0.0) ratio = f / reference_frequency;
    } catch (const InvalidInput&) {
      out.warnings.push_back("mesh '" + m.name +
                             "': not connected to the operating point; phase ratio 1 assumed");
    }
    const auto offset = phase_offsets.find(m.name);
    builder.AddMesh(m.name, body[p], body[w], G, std::move(built.core), std::nullopt, ratio,
                    offset != phase_offsets.end() ? offset->second : 0.0);
    out.mesh_angles.push_back(gamma[k]);
    out.drive_signs.push_back(built.drive_sign);
  }

  // ---- Loads (θz moments, all added).
  if (scene.operating_point.torque != 0.0) {
    Vector6 f = Vector6::Zero();
    f(5) = scene.operating_point.torque;
    builder.AddTorque(body[root], f, "operating_point");
  }
  for (const TorqueLoadDef& load : scene.loads) {
    Vector6 f = Vector6::Zero();
    f(5) = load.torque;
    // A rack's force along its direction of travel Z × ê, ê from its pinion to it.
    for (int k = 0; k < num_meshes && load.force != 0.0; ++k) {
      if (scene.meshes[k].gear != load.body) continue;
      f.head<3>() = load.force * Vector3(-std::sin(gamma[k]), std::cos(gamma[k]), 0.0);
    }
    builder.AddTorque(body[GearIndex(scene, load.body)], f, load.name);
  }

  out.model = builder.Build();
  if (options.mesh_preload && num_meshes > 0) {
    // The tangent stiffness about the loaded state: the static mesh forces of the model as built,
    // then K_g(F̄_η) per mesh (mesh_preload_stiffness.hpp). The preload is the mean load's, so
    // the statics' warnings (an unbalanced torque, an opened contact) are the preload's too.
    for (const MeshDef& m : scene.meshes) {
      GEARDYN_THROW_UNLESS(m.model.level != MeshModelLevel::kContact,
                           "mesh." << m.name << ".model: the mesh preload (--loaded) needs a "
                                   << "linear or slice mesh core, not \"contact\"");
    }
    const StaticDeflectionResult statics = SolveStaticDeflection(out.model);
    for (const std::string& w : statics.summary.warnings) {
      out.warnings.push_back("mesh preload: " + w);
    }
    for (int k = 0; k < num_meshes; ++k) {
      const MeshDef& m = scene.meshes[k];
      const MeshFrame& frame = frames[static_cast<std::size_t>(k)];
      const SystemMesh& mesh = out.model.meshes()[static_cast<std::size_t>(k)];
      const double force = statics.meshes[static_cast<std::size_t>(k)].force_eta;
      MeshPreload preload{
          m.name, force, CalcMeshPreloadCoefficient(frame, force),
          frame.rack ? 0.0 : (frame.gear_center - frame.pinion_center).dot(frame.v)};
      if (preload.coefficient != 0.0) {
        // The consistent tangent of the mean mesh energy ½ (δ − e)ᵀ K̄2 (δ − e) at the deflected
        // state q̄: with ∇δ_η(q̄) = G_η + (∇²δ_η q̄)ᵀ (the line of action turned by the static
        // relative shift), G'ᵀ K̄2 G' + F̄ ∇²δ_η; the element holds its difference from Gᵀ K̄2 G.
        const Matrix12 hessian = CalcMeshPreloadStiffness(frame, 1.0);
        Vector12 local = Vector12::Zero();
        for (int a = 0; a < 12; ++a) {
          if (mesh.dofs[a] >= 0) local(a) = statics.deflection(mesh.dofs[a]);
        }
        Matrix2x12 G_loaded = mesh.G;
        G_loaded.row(0) += (hessian * local).transpose();
        Matrix12 added = G_loaded.transpose() * mesh.mean_core_stiffness * G_loaded -
                         mesh.G.transpose() * mesh.mean_core_stiffness * mesh.G + force * hessian;
        added = 0.5 * (added + added.transpose());
        builder.AddElement(m.name + ".preload", ElementKind::kMeshPreload,
                           {body[GearIndex(scene, m.pinion)], body[GearIndex(scene, m.gear)]},
                           MatrixX(added));
      }
      out.mesh_preloads.push_back(std::move(preload));
    }
    const SystemModel plain = out.model;
    out.model = builder.Build();
    out.mesh_preload_rigid_modes = KeepRigidBodyModes(plain, &out.model);
  }
  if (options.planar || scene.planar) out.model = out.model.RestrictToPlanar();
  // After the restriction: the modes that modal damping refers to are the model's own.
  out.model = AddSystemDamping(out.model, scene.damping);
  return out;
}

SystemModel MakeSystemModel(const Scene& scene, const SceneSystemOptions& options) {
  return BuildSceneSystem(scene, options).model;
}

}  // namespace geardyn
