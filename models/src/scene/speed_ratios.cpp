#include "scene/speed_ratios.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "geardyn/models/scene/planetary.hpp"

namespace geardyn::internal {
namespace {

// One kinematic constraint Ω_b = factor · Ω_a between two gears.
struct Edge {
  std::string a;
  std::string b;
  double factor;
  std::optional<std::size_t> mesh;
  std::optional<std::size_t> bearing;
  std::optional<std::size_t> shaft;
};

// Relative tolerance of the loop check: ratios are products of a few tooth-count quotients.
constexpr double kLoopTol = 1e-9;

}  // namespace

SpeedRatios CalcSpeedRatios(const Scene& scene, std::string_view reference) {
  std::vector<Edge> edges;
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    const MeshDef& mesh = scene.meshes[i];
    if (scene.FindPlanetaryMesh(mesh.name)) continue;  // the set's own rule below
    const GearDef& pinion = scene.gear(mesh.pinion);
    const GearDef& gear = scene.gear(mesh.gear);
    if (gear.blank.kind == GearKind::kRack) continue;  // it translates: no angular speed
    const double sign = gear.blank.kind == GearKind::kInternal ? 1.0 : -1.0;
    edges.push_back(
        {mesh.pinion, mesh.gear,
         sign * static_cast<double>(pinion.blank.teeth) / static_cast<double>(gear.blank.teeth), i,
         std::nullopt, std::nullopt});
  }
  for (std::size_t i = 0; i < scene.bearings.size(); ++i) {
    const BearingDef& bearing = scene.bearings[i];
    if (!bearing.other.empty() && bearing.stiffness(5, 5) > 0.0) {
      edges.push_back({bearing.body, bearing.other, 1.0, std::nullopt, i, std::nullopt});
    }
  }
  // A gear on a shaft turns with it (the shaft name is a node of the graph).
  for (std::size_t i = 0; i < scene.shafts.size(); ++i) {
    for (const ShaftGearDef& g : scene.shafts[i].gears) {
      edges.push_back({scene.shafts[i].name, g.gear, 1.0, std::nullopt, std::nullopt, i});
    }
  }

  // Planetary sets: Ω_m = a_m t for every member (Willis, planetary.hpp).
  std::vector<std::map<std::string, double, std::less<>>> sets;
  for (const PlanetaryDef& set : scene.planetaries) sets.push_back(PlanetarySpeedFactors(set));
  // t of set s from its first member with a known ratio and a_m ≠ 0, if any.
  const auto set_t = [&](const auto& factors, const SpeedRatios& r) -> std::optional<double> {
    for (const auto& [member, a] : factors) {
      const auto it = r.ratio.find(member);
      if (a != 0.0 && it != r.ratio.end()) return it->second / a;
    }
    return std::nullopt;
  };

  SpeedRatios result;
  result.ratio.emplace(std::string(reference), 1.0);
  // Relaxation over the (small) edge list until nothing changes: a breadth-first spanning tree.
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto& factors : sets) {
      const std::optional<double> t = set_t(factors, result);
      if (!t) continue;
      for (const auto& [member, a] : factors) {
        if (result.ratio.emplace(member, a * *t).second) changed = true;
      }
    }
    for (const Edge& e : edges) {
      const auto ia = result.ratio.find(e.a);
      const auto ib = result.ratio.find(e.b);
      if (ia != result.ratio.end() && ib == result.ratio.end()) {
        result.ratio.emplace(e.b, e.factor * ia->second);
        changed = true;
      } else if (ib != result.ratio.end() && ia == result.ratio.end()) {
        result.ratio.emplace(e.a, ib->second / e.factor);
        changed = true;
      }
    }
  }
  // Every planetary member must agree with its set's t.
  for (std::size_t s = 0; s < sets.size(); ++s) {
    const std::optional<double> t = set_t(sets[s], result);
    if (!t) continue;
    for (const auto& [member, a] : sets[s]) {
      const double known = result.ratio.at(member);
      const double implied = a * *t;
      if (std::abs(known - implied) > kLoopTol * std::max(std::abs(known), std::abs(implied))) {
        const std::string& first_mesh = scene.planetaries[s].sun_meshes.front();
        for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
          if (scene.meshes[i].name == first_mesh) result.conflict_mesh = i;
        }
        result.conflict_gear = member;
        result.ratio_known = known;
        result.ratio_implied = implied;
        return result;
      }
    }
  }
  // Every edge must now agree with the ratios (loops of meshes must close).
  for (const Edge& e : edges) {
    const auto ia = result.ratio.find(e.a);
    const auto ib = result.ratio.find(e.b);
    if (ia == result.ratio.end() || ib == result.ratio.end()) continue;
    const double implied = e.factor * ia->second;
    if (std::abs(ib->second - implied) >
        kLoopTol * std::max(std::abs(ib->second), std::abs(implied))) {
      result.conflict_mesh = e.mesh;
      result.conflict_bearing = e.bearing;
      result.conflict_shaft = e.shaft;
      result.conflict_gear = e.b;
      result.ratio_known = ib->second;
      result.ratio_implied = implied;
      break;
    }
  }
  return result;
}

}  // namespace geardyn::internal
