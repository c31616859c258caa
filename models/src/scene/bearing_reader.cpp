// Reading one [[bearing]] table: the bodies it connects and its 6×6 stiffness and damping.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/element_names.hpp"
#include "scene/section_readers.hpp"
#include "scene/suggestions.hpp"
#include "scene/toml_fields.hpp"

namespace geardyn::internal {
namespace {

constexpr std::array<const char*, 6> kDofNames = {"x", "y", "z", "rx", "ry", "rz"};
// Relative tolerances: this only absorbs the rounding of hand-typed symmetric matrices.
constexpr double kSymmetryTol = 1e-9;
constexpr double kPsdTol = 1e-9;  // on the diagonally scaled matrix (unit diagonal)

std::string Index2(int i, int j) {
  return "[" + std::to_string(i) + "][" + std::to_string(j) + "]";
}

// A diagonal matrix from an array of 6 numbers, each >= 0.
Matrix6 ReadDiagonal(const ErrorContext& ctx, const toml::array& a, const std::string& key) {
  Matrix6 m = Matrix6::Zero();
  for (int i = 0; i < 6; ++i) {
    const toml::node& e = *a.get(static_cast<std::size_t>(i));
    const std::string pos = std::to_string(i) + " (" + kDofNames[i] + ")";
    if (e.is_array()) ctx.Fail(&e, key, "mixes numbers and rows: entry " + pos + " is an array");
    m(i, i) = ReadFiniteNumber(ctx, e, key, "entry " + pos + " ");
    if (m(i, i) < 0.0) {
      ctx.Fail(&e, key, "diagonal entry " + pos + " must be >= 0, got " + FormatNumber(m(i, i)));
    }
  }
  return m;
}

// A full matrix from an array of 6 rows of 6 numbers, checked symmetric and symmetrized.
Matrix6 ReadFull(const ErrorContext& ctx, const toml::array& a, const std::string& key) {
  Matrix6 m = Matrix6::Zero();
  for (int i = 0; i < 6; ++i) {
    const toml::node& r = *a.get(static_cast<std::size_t>(i));
    const toml::array* row = r.as_array();
    if (row == nullptr) {
      ctx.Fail(&r, key, "mixes numbers and rows: row " + std::to_string(i) + " is " + Describe(r));
    }
    if (row->size() != 6) {
      ctx.Fail(&r, key,
               "row " + std::to_string(i) + " (" + kDofNames[i] + ") must have 6 entries, got " +
                   std::to_string(row->size()));
    }
    for (int j = 0; j < 6; ++j) {
      m(i, j) = ReadFiniteNumber(ctx, *row->get(static_cast<std::size_t>(j)), key,
                                 "entry " + Index2(i, j) + " ");
    }
  }
  for (int i = 0; i < 6; ++i) {
    for (int j = i + 1; j < 6; ++j) {
      if (std::abs(m(i, j) - m(j, i)) >
          kSymmetryTol * std::max(std::abs(m(i, j)), std::abs(m(j, i)))) {
        ctx.Fail(a.get(static_cast<std::size_t>(j)), key,
                 "not symmetric: " + Index2(i, j) + " (" + kDofNames[i] + "," + kDofNames[j] +
                     ") = " + FormatNumber(m(i, j)) + " but " + Index2(j, i) + " = " +
                     FormatNumber(m(j, i)));
      }
    }
  }
  return (0.5 * (m + m.transpose())).eval();
}

// Rejects a symmetric matrix that is not positive semi-definite. The entries mix units (N/m,
// N/rad, N m/rad), so the test is on the diagonally scaled matrix S K S with
// S = diag(1/sqrt(K_ii)), whose eigenvalues are unit-free.
void CheckPositiveSemiDefinite(const Fields& f, std::string_view key, const toml::array& a,
                               const Matrix6& m) {
  const ErrorContext& ctx = f.context();
  const std::string k = f.Key(key);
  for (int i = 0; i < 6; ++i) {
    const toml::node* row = a.get(static_cast<std::size_t>(i));
    if (m(i, i) < 0.0) {
      ctx.Fail(row, k,
               "not positive semi-definite: diagonal entry " + Index2(i, i) + " (" + kDofNames[i] +
                   ") = " + FormatNumber(m(i, i)) + " < 0");
    }
    if (m(i, i) == 0.0) {
      for (int j = 0; j < 6; ++j) {
        if (m(i, j) != 0.0) {
          ctx.Fail(row, k,
                   "not positive semi-definite: diagonal entry " + Index2(i, i) + " (" +
                       kDofNames[i] + ") is 0 but " + Index2(i, j) + " = " + FormatNumber(m(i, j)));
        }
      }
    }
  }
  Vector6 s;
  for (int i = 0; i < 6; ++i) s(i) = m(i, i) > 0.0 ? 1.0 / std::sqrt(m(i, i)) : 1.0;
  const Matrix6 scaled = s.asDiagonal() * m * s.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Matrix6> eig(scaled, Eigen::EigenvaluesOnly);
  const double lowest = eig.eigenvalues()(0);
  if (lowest < -kPsdTol) {
    f.Fail(key, "not positive semi-definite: the diagonally scaled matrix has eigenvalue " +
                    FormatNumber(lowest) +
                    " < 0 (off-diagonal couplings too large for the diagonal)");
  }
}

}  // namespace

// A symmetric positive semi-definite 6×6 matrix: 6 numbers (diagonal) or 6 rows of 6.
Matrix6 ReadMatrix6(const Fields& f, std::string_view key, const std::string& what) {
  const toml::node* n = f.Find(key);
  const std::string forms =
      "an array of 6 numbers (diagonal) or of 6 rows of 6 numbers (full symmetric matrix)";
  if (n == nullptr) f.Missing(key, what + ": " + forms);
  const toml::array* a = n->as_array();
  if (a == nullptr) f.Fail(key, "must be " + forms + ", got " + Describe(*n));
  const bool rows = a->size() > 0 && a->get(0)->is_array();
  if (a->size() != 6) {
    f.Fail(key, "must have 6 entries (diagonal) or 6 rows of 6 (full matrix), got " +
                    std::to_string(a->size()) + (rows ? " rows" : " entries"));
  }
  if (!rows) return ReadDiagonal(f.context(), *a, f.Key(key));
  const Matrix6 m = ReadFull(f.context(), *a, f.Key(key));
  CheckPositiveSemiDefinite(f, key, *a, m);
  return m;
}

namespace {

// The shaft named `name`, if any.
const ShaftDef* FindShaft(const Scene& scene, const std::string& name) {
  for (const ShaftDef& s : scene.shafts) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

// A gear or shaft name under `key` (`station_key` is the station required on a shaft).
void CheckBody(const Fields& f, std::string_view key, std::string_view station_key,
               const std::string& name, const Scene& scene, std::optional<double>* station) {
  const ShaftDef* shaft = FindShaft(scene, name);
  if (shaft == nullptr) {
    bool gear = false;
    for (const GearDef& g : scene.gears) gear = gear || g.name == name;
    if (!gear && !scene.shafts.empty()) {
      std::vector<std::string> names;
      for (const GearDef& g : scene.gears) names.push_back(g.name);
      for (const ShaftDef& s : scene.shafts) names.push_back(s.name);
      f.Fail(key, "no gear or shaft named '" + name + "'" + DidYouMean(name, names) +
                      "; gears and shafts: " + JoinNames(names));
    }
    (void)GearByName(f, key, name, scene);
    if (f.Find(station_key) != nullptr) {
      f.Fail(station_key, "only a bearing on a [[shaft]] has a station; '" + name + "' is a gear");
    }
    return;
  }
  *station = ReadStation(f, station_key, *shaft);
}

}  // namespace

BearingDef ReadBearing(const ErrorContext& ctx, const toml::table& t, std::size_t index,
                       const Scene& scene) {
  BearingDef bd;
  CheckElementKeys(ctx, t, "bearing", index,
                   {"name", "body", "other", "station", "other_station", "stiffness", "damping"});
  bd.name = ReadElementName(ctx, t, "bearing", index);
  const Fields f(ctx, t, "bearing." + bd.name);
  bd.body = f.ReqString("body", "name of the supported [[gear]] or [[shaft]]");
  CheckBody(f, "body", "station", bd.body, scene, &bd.station);
  if (auto other = f.OptString("other")) {
    bd.other = *other;
    CheckBody(f, "other", "other_station", bd.other, scene, &bd.other_station);
    if (bd.other == bd.body && bd.station == bd.other_station) {
      f.Fail("other", "must differ from body ('" + bd.body + "'); omit it for a ground bearing");
    }
  } else if (f.Find("other_station") != nullptr) {
    f.Fail("other_station", "only a bearing with an `other` shaft has an other_station");
  }
  bd.stiffness = ReadMatrix6(f, "stiffness", "stiffness in N/m, N/rad, N m/rad");
  if (f.Find("damping") != nullptr) {
    bd.damping = ReadMatrix6(f, "damping", "damping in N s/m, N s/rad, N m s/rad");
  }
  return bd;
}

}  // namespace geardyn::internal
