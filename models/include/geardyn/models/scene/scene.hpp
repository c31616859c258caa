/// @file
/// @brief The validated, SI description of a geared system as read from a scene file: gears,
/// meshes (with their derived pair geometry), bearings, external torques and the operating point.
///
/// A Scene is plain data produced by the scene reader (scene_reader.hpp), which converts degrees
/// and rpm to radians and rad/s and rejects anything inconsistent. Every quantity here is SI:
/// lengths in m, angles in rad, speeds in rad/s, masses in kg, inertias in kg m², torques in N·m.
/// The file format is documented in docs/scene-format.md.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/models/gear/gear_geometry.hpp"
#include "geardyn/models/scene/mesh_model.hpp"

namespace geardyn {

/// @brief One gear body: its tooth/blank data and its rigid-body mass properties.
struct GearDef {
  std::string name;                          ///< unique among the scene's gears
  GearBlank blank;                           ///< teeth, kind, face width, rack, tip, web, rim
  double normal_module = 0.0;                ///< m_n [m]
  double normal_pressure_angle = 0.0;        ///< α_n [rad]
  double helix_angle = 0.0;                  ///< β at the reference circle [rad], ≥ 0
  HelixHand hand = HelixHand::kNone;         ///< kNone iff helix_angle == 0
  double mass = 0.0;                         ///< m [kg], > 0
  double inertia = 0.0;                      ///< polar moment of inertia about the axis [kg m²]
  std::optional<double> transverse_inertia;  ///< about a diameter through the centre [kg m²]
};

/// @brief One gear mesh between two gears of the scene, with its derived pair geometry and the
/// mesh model the scene asks for.
struct MeshDef {
  std::string name;           ///< unique among the meshes; default "<pinion>-<gear>"
  std::string pinion;         ///< name of the driving member (never an internal gear)
  std::string gear;           ///< name of the driven member (may be internal)
  GearPairGeometry geometry;  ///< CalcGearPairGeometry of the two gears' data
  /// The requested mesh model: level, stiffness source, modifications, errors, damping, user
  /// parameters (mesh_model.hpp; BuildMeshCore makes its MeshCore).
  MeshModelDef model;
};

/// @brief A linear 6-DOF spring-damper between a gear body and the ground or another gear.
///
/// DOF order of both matrices: x, y, z, θx, θy, θz of the body (z along the gear axis). Entry
/// units follow from the DOF pair: N/m (translation–translation), N·m/rad (rotation–rotation),
/// N/rad = N·m/m (mixed); damping the same per second (N·s/m, N·m·s/rad, N·s/rad). Both are
/// symmetric positive semi-definite. With another body the element acts on the relative motion
/// (body − other).
struct BearingDef {
  std::string name;   ///< unique among the bearings; default "bearing<i>" (0-based i)
  std::string body;   ///< gear name
  std::string other;  ///< gear name, empty = ground
  Matrix6 stiffness = Matrix6::Zero();  ///< K [N/m, N·m/rad, N/rad], symmetric PSD
  Matrix6 damping = Matrix6::Zero();    ///< C [N·s/m, N·m·s/rad, N·s/rad], symmetric PSD
};

/// @brief A constant external torque on a gear body.
struct TorqueLoadDef {
  std::string name;     ///< unique among the loads; default "load<i>" (0-based i)
  std::string body;     ///< gear name
  double torque = 0.0;  ///< [N·m] about the body's own axis (θz), signed
};

/// @brief Speed and mean torque of the reference gear.
struct OperatingPointDef {
  std::string body;     ///< reference gear; default the first mesh's pinion
  double speed = 0.0;   ///< Ω of the reference gear [rad/s], ≥ 0 (the positive direction)
  double torque = 0.0;  ///< mean torque on the reference gear [N·m], signed
};

/// @brief A validated scene (see docs/scene-format.md for the file format).
struct Scene {
  std::string source;  ///< file path or "builtin:NAME" it was read from
  std::string title;   ///< free text, may be empty
  std::vector<GearDef> gears;
  std::vector<MeshDef> meshes;
  std::vector<BearingDef> bearings;
  std::vector<TorqueLoadDef> loads;
  OperatingPointDef operating_point;

  /// @brief The gear named `name`.
  /// @throws InvalidInput if the scene has no such gear.
  const GearDef& gear(std::string_view name) const;

  /// @brief Signed angular speed of gear `name` [rad/s] at the operating point.
  ///
  /// Propagated from the operating point's reference gear (speed Ω_ref ≥ 0, the positive
  /// direction about the common +z axis) through the meshes: across a mesh between gears i and
  /// j, Ω_j = ∓ Ω_i z_i / z_j (minus for an external mesh, which reverses the direction, plus for
  /// an internal one). A bearing between two gears with a torsional stiffness
  /// (stiffness(5, 5) > 0) ties them to the same speed (two gears on one shaft).
  /// @throws InvalidInput if there is no such gear or it is not connected to the reference gear
  ///   through meshes (and torsionally stiff bearings).
  double GearSpeed(std::string_view name) const;

  /// @brief Tooth-mesh frequency of `mesh` [Hz]: |Ω_pinion| z_pinion / (2π).
  /// @throws InvalidInput if the mesh's pinion is not connected to the reference gear.
  double MeshFrequencyHz(const MeshDef& mesh) const;
};

}  // namespace geardyn
