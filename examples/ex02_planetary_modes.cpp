// geardyn example 2 — the modes of a planetary gear set and their Lin & Parker types.
//
// Builds a built-in planetary scene (default `builtin:planetary-lin-parker`: a spur set with
// 4 equally spaced planets and the system parameters of Lin & Parker 1999, Table 1;
// examples/scenes/planetary-lin-parker.toml) into a SystemModel, computes the modes of its mean
// (LTI) system and prints, per distinct frequency: the frequency, its multiplicity, the planetary
// mode type (rotational / translational / planet, Lin & Parker 1999, J. Sound Vib. 228(1)) and
// the kinetic-energy share of the central members (sun, ring, carrier) and of the planets. A
// summary line counts the types; for N equally spaced planets the planar model has 6 rotational
// modes, 6 translational pairs and 3 planet-mode frequencies of multiplicity N − 3.
//
// Sample runs:
//   ./examples/ex02_planetary_modes                                   (6-DOF bodies, N = 4)
//   ./examples/ex02_planetary_modes builtin:planetary-lin-parker planar=true
//   ./examples/ex02_planetary_modes builtin:planetary-lin-parker planar=true planetary.0.planets=3
//   ./examples/ex02_planetary_modes builtin:planetary-wind-turbine
// Every argument after the scene is a `--set` override (docs/scene-format.md).
//
// Illustrates: planetary scenes ([[planetary]], docs/scene-format.md), spec 02 "Eigen (LTI)" with
// the planetary labels of ComputeModes. See first ex01_helical_pair_modes.
#include <cstdio>
#include <exception>
#include <map>
#include <string>
#include <vector>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"

int main(int argc, char** argv) {
  using namespace geardyn;
  const std::string source = argc > 1 ? argv[1] : "builtin:planetary-lin-parker";
  std::vector<std::string> overrides(argv + (argc > 1 ? 2 : 1), argv + argc);
  try {
    const Scene scene = LoadScene(source, overrides);
    const SystemModel model = MakeSystemModel(scene);
    const ModalResult modes = ComputeModes(model);
    const DofMap& dofs = model.dof_map();

    std::printf("%s: %d DOFs (%s), %d planets, %d modes, status %s\n\n", source.c_str(),
                model.num_dofs(), scene.planar ? "planar" : "6 per body", dofs.num_planets(),
                static_cast<int>(modes.frequencies_hz.size()), StatusName(modes.summary.status));
    if (modes.planetary_labels.empty()) {
      std::printf("no planets in this scene: no planetary mode types\n");
      return 0;
    }
    std::printf("%5s %12s %5s  %-14s %8s %8s\n", "modes", "f [Hz]", "mult", "type", "central",
                "planets");
    std::map<std::string, int> count;  // "type ×multiplicity" → number of frequencies
    for (const std::vector<int>& group : modes.multiplicity_groups) {
      const int k = group.front();
      double planets = 0.0;
      for (int b = 0; b < model.num_bodies(); ++b) {
        if (dofs.body_role(BodyIndex(b)) == BodyRole::kPlanet) {
          planets += modes.body_kinetic_fractions(k, b);
        }
      }
      const char* type = ToString(modes.planetary_labels[static_cast<std::size_t>(k)]);
      std::printf("%2d-%-2d %12.2f %5d  %-14s %7.1f%% %7.1f%%\n", group.front(), group.back(),
                  modes.frequencies_hz(k), static_cast<int>(group.size()), type,
                  100.0 * (1.0 - planets), 100.0 * planets);
      ++count[std::string(type) + " x" + std::to_string(group.size())];
    }
    std::printf("\nfrequencies per type and multiplicity:");
    for (const auto& [key, n] : count) std::printf("  %s: %d", key.c_str(), n);
    std::printf("\n");
    for (const std::string& w : modes.summary.warnings) std::printf("warning: %s\n", w.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
