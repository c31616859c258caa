#include "scene/speed_ratios.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace geardyn::internal {
namespace {

// One kinematic constraint Ω_b = factor · Ω_a between two gears.
struct Edge {
  std::string a;
  std::string b;
  double factor;
  std::optional<std::size_t> mesh;
  std::optional<std::size_t> bearing;
};

// Relative tolerance of the loop check: ratios are products of a few tooth-count quotients.
constexpr double kLoopTol = 1e-9;

}  // namespace

SpeedRatios CalcSpeedRatios(const Scene& scene, std::string_view reference) {
  std::vector<Edge> edges;
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    const MeshDef& mesh = scene.meshes[i];
    const GearDef& pinion = scene.gear(mesh.pinion);
    const GearDef& gear = scene.gear(mesh.gear);
    const double sign = gear.blank.kind == GearKind::kInternal ? 1.0 : -1.0;
    edges.push_back(
        {mesh.pinion, mesh.gear,
         sign * static_cast<double>(pinion.blank.teeth) / static_cast<double>(gear.blank.teeth), i,
         std::nullopt});
  }
  for (std::size_t i = 0; i < scene.bearings.size(); ++i) {
    const BearingDef& bearing = scene.bearings[i];
    if (!bearing.other.empty() && bearing.stiffness(5, 5) > 0.0) {
      edges.push_back({bearing.body, bearing.other, 1.0, std::nullopt, i});
    }
  }

  SpeedRatios result;
  result.ratio.emplace(std::string(reference), 1.0);
  // Relaxation over the (small) edge list until nothing changes: a breadth-first spanning tree.
  for (bool changed = true; changed;) {
    changed = false;
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
      result.conflict_gear = e.b;
      result.ratio_known = ib->second;
      result.ratio_implied = implied;
      break;
    }
  }
  return result;
}

}  // namespace geardyn::internal
