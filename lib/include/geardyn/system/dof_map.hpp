/// @file
/// @brief DofMap: the bodies of an assembled system and the numbering, kind and names of their
/// degrees of freedom (spec 01 §1; architecture §3.2, §3.5 strong index types).
///
/// Every body has six small-motion coordinates of its reference point (its centre),
/// q_b = [x, y, z, θx, θy, θz] [m, m, m, rad, rad, rad], in a frame parallel to the inertial one
/// whose Z axis is the body's axis of rotation (spec 01 §1). The full system numbers them
/// body-major: DOF 6·b + c for body b and component c. A restricted system (a decoupled block,
/// or the planar x, y, θz model) keeps a subset of them, in increasing full-system order; the
/// map then knows which (body, component) each kept DOF is and which are held fixed.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace geardyn {

/// @brief An integer index that does not mix with other kinds of index (Drake TypeSafeIndex).
/// Converts implicitly to int for use as a subscript; construction from int is explicit.
template <typename Tag>
class TypeSafeIndex {
 public:
  constexpr TypeSafeIndex() = default;
  constexpr explicit TypeSafeIndex(int value) : value_(value) {}
  /// The raw index (−1 when default-constructed: invalid).
  constexpr int value() const { return value_; }
  constexpr operator int() const { return value_; }  // NOLINT(google-explicit-constructor)
  /// True when the index is ≥ 0.
  constexpr bool is_valid() const { return value_ >= 0; }
  friend constexpr bool operator==(TypeSafeIndex a, TypeSafeIndex b) = default;

 private:
  int value_ = -1;
};

/// Index of a body in a DofMap / SystemModel.
using BodyIndex = TypeSafeIndex<struct BodyIndexTag>;
/// Index of a mesh in a SystemModel.
using MeshIndex = TypeSafeIndex<struct MeshIndexTag>;
/// Index of an element (bearing, shaft, coupling, spring) in a SystemModel.
using ElementIndex = TypeSafeIndex<struct ElementIndexTag>;

/// Number of coordinates of one body.
inline constexpr int kBodyDofs = 6;

/// @brief The six coordinates of a body, in storage order.
enum class BodyDof { kX = 0, kY = 1, kZ = 2, kThetaX = 3, kThetaY = 4, kThetaZ = 5 };

/// @brief Physical kind of a body coordinate relative to the body's axis Z.
enum class DofKind {
  kTranslationTransverse,  ///< x, y [m]
  kTranslationAxial,       ///< z [m]
  kRotationAxial,          ///< θz [rad] (torsional)
  kRotationTilt,           ///< θx, θy [rad] (rocking)
};

/// @brief What a body is in a planetary (epicyclic) gear set, for mode classification (Lin &
/// Parker 1999: central members — sun, ring, carrier — lie on the set's axis; planets around it).
/// kOther for every body that is not part of a planetary set.
enum class BodyRole { kOther, kSun, kRing, kCarrier, kPlanet };
/// "other", "sun", "ring", "carrier", "planet".
const char* ToString(BodyRole role);

/// Kind of component c ∈ [0, 6) of a body (x, y → transverse; z → axial; θx, θy → tilt; θz →
/// torsional).
DofKind DofKindOf(BodyDof component);
/// Short name "translation_transverse", "translation_axial", "rotation_axial", "rotation_tilt".
const char* ToString(DofKind kind);
/// Component name "x", "y", "z", "θx", "θy", "θz".
const char* ToString(BodyDof component);

/// @brief Bodies and DOF numbering of a system; immutable once built, cheap to copy.
class DofMap {
 public:
  /// Empty map (no bodies).
  DofMap() = default;

  /// @brief The full map: all six DOFs of every body, DOF 6·b + c.
  /// @param[in] body_names unique, non-empty names.
  /// @throws InvalidInput on an empty or duplicate name.
  explicit DofMap(std::vector<std::string> body_names);

  /// @brief The full map with a role per body (planetary sets; see BodyRole).
  /// @param[in] body_roles one per body.
  /// @throws InvalidInput as above, or when the sizes differ.
  DofMap(std::vector<std::string> body_names, std::vector<BodyRole> body_roles);

  /// @brief The map restricted to some DOFs of this map (others held fixed).
  /// @param[in] dofs indices into THIS map, strictly increasing.
  /// @throws InvalidInput on an out-of-range or non-increasing index.
  DofMap Restrict(const std::vector<int>& dofs) const;

  /// Number of bodies.
  int num_bodies() const { return static_cast<int>(body_names_.size()); }
  /// Number of DOFs kept (6·num_bodies for a full map).
  int num_dofs() const { return static_cast<int>(dof_body_.size()); }
  /// True when every body keeps all six DOFs.
  bool is_full() const { return num_dofs() == kBodyDofs * num_bodies(); }

  /// Name of body b. @throws InvalidInput if b is out of range.
  const std::string& body_name(BodyIndex b) const;
  /// Role of body b (kOther unless set). @throws InvalidInput if b is out of range.
  BodyRole body_role(BodyIndex b) const;
  /// Number of bodies with role kPlanet.
  int num_planets() const;
  /// The body called `name`, if any.
  std::optional<BodyIndex> FindBody(std::string_view name) const;
  /// The body called `name`. @throws InvalidInput naming it (and the known bodies) if absent.
  BodyIndex GetBody(std::string_view name) const;

  /// DOF index of (body, component), or −1 if that coordinate is held fixed in this map.
  int FindDof(BodyIndex body, BodyDof component) const;
  /// DOF index of (body, component). @throws InvalidInput if it is not kept.
  int dof(BodyIndex body, BodyDof component) const;
  /// The six DOF indices of a body (−1 for coordinates held fixed).
  std::array<int, kBodyDofs> body_dofs(BodyIndex body) const;

  /// Body of DOF i.
  BodyIndex dof_body(int i) const { return dof_body_.at(i); }
  /// Component of DOF i.
  BodyDof dof_component(int i) const { return dof_component_.at(i); }
  /// Kind of DOF i.
  DofKind dof_kind(int i) const { return DofKindOf(dof_component(i)); }
  /// Name of DOF i: "<body>.<component>", e.g. "wheel.θz".
  std::string dof_name(int i) const;
  /// Index of DOF i in the full (unrestricted) map: 6·body + component.
  int full_index(int i) const {
    return kBodyDofs * dof_body(i).value() + static_cast<int>(dof_component(i));
  }

 private:
  std::vector<std::string> body_names_;
  std::vector<BodyRole> body_roles_;  // one per body
  std::vector<BodyIndex> dof_body_;
  std::vector<BodyDof> dof_component_;
  std::vector<int> full_to_kept_;  // (6·num_bodies) kept index or −1
};

}  // namespace geardyn
