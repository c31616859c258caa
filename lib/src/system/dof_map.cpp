#include "geardyn/system/dof_map.hpp"

#include <sstream>

#include "geardyn/common/check.hpp"

namespace geardyn {

DofKind DofKindOf(BodyDof component) {
  switch (component) {
    case BodyDof::kX:
    case BodyDof::kY:
      return DofKind::kTranslationTransverse;
    case BodyDof::kZ:
      return DofKind::kTranslationAxial;
    case BodyDof::kThetaX:
    case BodyDof::kThetaY:
      return DofKind::kRotationTilt;
    case BodyDof::kThetaZ:
      return DofKind::kRotationAxial;
  }
  GEARDYN_DEMAND(false);
}

const char* ToString(DofKind kind) {
  switch (kind) {
    case DofKind::kTranslationTransverse:
      return "translation_transverse";
    case DofKind::kTranslationAxial:
      return "translation_axial";
    case DofKind::kRotationAxial:
      return "rotation_axial";
    case DofKind::kRotationTilt:
      return "rotation_tilt";
  }
  return "?";
}

const char* ToString(BodyDof component) {
  switch (component) {
    case BodyDof::kX:
      return "x";
    case BodyDof::kY:
      return "y";
    case BodyDof::kZ:
      return "z";
    case BodyDof::kThetaX:
      return "θx";
    case BodyDof::kThetaY:
      return "θy";
    case BodyDof::kThetaZ:
      return "θz";
  }
  return "?";
}

const char* ToString(BodyRole role) {
  switch (role) {
    case BodyRole::kOther:
      return "other";
    case BodyRole::kSun:
      return "sun";
    case BodyRole::kRing:
      return "ring";
    case BodyRole::kCarrier:
      return "carrier";
    case BodyRole::kPlanet:
      return "planet";
  }
  return "?";
}

DofMap::DofMap(std::vector<std::string> body_names, std::vector<BodyRole> body_roles)
    : DofMap(std::move(body_names)) {
  GEARDYN_THROW_UNLESS(
      body_roles.size() == body_names_.size(),
      "body_roles: " << body_roles.size() << " roles for " << body_names_.size() << " bodies");
  body_roles_ = std::move(body_roles);
}

BodyRole DofMap::body_role(BodyIndex b) const {
  GEARDYN_THROW_UNLESS(b.value() >= 0 && b.value() < num_bodies(),
                       "body index " << b.value() << ": out of range [0, " << num_bodies() << ")");
  return body_roles_[b.value()];
}

int DofMap::num_planets() const {
  int n = 0;
  for (BodyRole r : body_roles_) n += r == BodyRole::kPlanet ? 1 : 0;
  return n;
}

DofMap::DofMap(std::vector<std::string> body_names) : body_names_(std::move(body_names)) {
  body_roles_.assign(body_names_.size(), BodyRole::kOther);
  for (std::size_t b = 0; b < body_names_.size(); ++b) {
    GEARDYN_THROW_UNLESS(!body_names_[b].empty(), "body " << b << ": empty name");
    for (std::size_t a = 0; a < b; ++a) {
      GEARDYN_THROW_UNLESS(
          body_names_[a] != body_names_[b],
          "body '" << body_names_[b] << "': duplicate name (bodies " << a << " and " << b << ")");
    }
  }
  const int n = kBodyDofs * num_bodies();
  dof_body_.reserve(n);
  dof_component_.reserve(n);
  full_to_kept_.resize(n);
  for (int i = 0; i < n; ++i) {
    dof_body_.push_back(BodyIndex(i / kBodyDofs));
    dof_component_.push_back(static_cast<BodyDof>(i % kBodyDofs));
    full_to_kept_[i] = i;
  }
}

DofMap DofMap::Restrict(const std::vector<int>& dofs) const {
  DofMap out;
  out.body_names_ = body_names_;
  out.body_roles_ = body_roles_;
  out.full_to_kept_.assign(full_to_kept_.size(), -1);
  int previous = -1;
  for (std::size_t k = 0; k < dofs.size(); ++k) {
    const int i = dofs[k];
    GEARDYN_THROW_UNLESS(i >= 0 && i < num_dofs(),
                         "dofs[" << k << "] = " << i << ": out of range [0, " << num_dofs() << ")");
    GEARDYN_THROW_UNLESS(i > previous,
                         "dofs[" << k << "] = " << i << ": indices must be strictly increasing");
    previous = i;
    out.dof_body_.push_back(dof_body_[i]);
    out.dof_component_.push_back(dof_component_[i]);
    out.full_to_kept_[full_index(i)] = static_cast<int>(k);
  }
  return out;
}

const std::string& DofMap::body_name(BodyIndex b) const {
  GEARDYN_THROW_UNLESS(b.value() >= 0 && b.value() < num_bodies(),
                       "body index " << b.value() << ": out of range [0, " << num_bodies() << ")");
  return body_names_[b.value()];
}

std::optional<BodyIndex> DofMap::FindBody(std::string_view name) const {
  for (int b = 0; b < num_bodies(); ++b) {
    if (body_names_[b] == name) return BodyIndex(b);
  }
  return std::nullopt;
}

BodyIndex DofMap::GetBody(std::string_view name) const {
  const std::optional<BodyIndex> b = FindBody(name);
  if (!b) {
    std::ostringstream known;
    for (int i = 0; i < num_bodies(); ++i) known << (i ? ", " : "") << "'" << body_names_[i] << "'";
    GEARDYN_THROW_UNLESS(false, "body '" << name << "': unknown (bodies: " << known.str() << ")");
  }
  return *b;
}

int DofMap::FindDof(BodyIndex body, BodyDof component) const {
  GEARDYN_THROW_UNLESS(
      body.value() >= 0 && body.value() < num_bodies(),
      "body index " << body.value() << ": out of range [0, " << num_bodies() << ")");
  return full_to_kept_[kBodyDofs * body.value() + static_cast<int>(component)];
}

int DofMap::dof(BodyIndex body, BodyDof component) const {
  const int i = FindDof(body, component);
  GEARDYN_THROW_UNLESS(i >= 0, "DOF " << body_names_[body.value()] << "." << ToString(component)
                                      << ": held fixed in this (restricted) system");
  return i;
}

std::array<int, kBodyDofs> DofMap::body_dofs(BodyIndex body) const {
  std::array<int, kBodyDofs> out{};
  for (int c = 0; c < kBodyDofs; ++c) out[c] = FindDof(body, static_cast<BodyDof>(c));
  return out;
}

std::string DofMap::dof_name(int i) const {
  return body_names_.at(dof_body(i).value()) + "." + ToString(dof_component(i));
}

}  // namespace geardyn
