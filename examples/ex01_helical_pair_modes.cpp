// geardyn example 1 — the modes of a helical pair on bearings, with the mode-type table.
//
// Builds the built-in scene `builtin:helical-pair` (z 25/61, m_n 3 mm, β 15°, each gear a rigid
// 6-DOF body on two rolling bearings; examples/scenes/helical-pair.toml) into a SystemModel,
// computes the modes of its mean (LTI) system with ComputeModes and prints, per mode: the
// frequency, the mode-type label, the kinetic-energy fractions in the torsional (θz), transverse
// (x, y), axial (z) and rocking (θx, θy) coordinates, and the part that stores the most strain
// energy (the mesh or a bearing). The rigid-body mode (nothing grounds the rotation of the
// train) appears at 0 Hz with a warning.
//
// Sample runs:
//   ./examples/ex01_helical_pair_modes
//   ./examples/ex01_helical_pair_modes builtin:kahraman-blankenship-rig
//   ./examples/ex01_helical_pair_modes my_scene.toml
// The same table from the command line: `geardyn modes builtin:helical-pair`.
//
// Illustrates: spec 02 "Eigen (LTI)" (modes of the mean system, rigid-body modes, energy
// classification), spec 01 §3 (the B–S mesh couples torsion, translation, axial motion and
// rocking of a helical pair). First example: see the README for building.
#include <cstdio>
#include <exception>
#include <string>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"

int main(int argc, char** argv) {
  using namespace geardyn;
  const std::string source = argc > 1 ? argv[1] : "builtin:helical-pair";
  try {
    const SystemModel model = MakeSystemModel(LoadScene(source));
    const ModalResult modes = ComputeModes(model);  // all modes (dense: 12 DOFs), with fractions

    std::printf("%s: %d DOFs, %d modes, method %s, status %s\n\n", source.c_str(), model.num_dofs(),
                static_cast<int>(modes.frequencies_hz.size()), ToString(modes.method_used),
                StatusName(modes.summary.status));
    std::printf("%4s %12s  %-14s %9s %10s %7s %8s   %s\n", "mode", "f [Hz]", "type", "torsional",
                "transverse", "axial", "rocking", "largest strain energy");
    const auto kinetic = [&](Eigen::Index k, DofKind kind) {
      return 100.0 * modes.kinetic_fractions(k, static_cast<int>(kind));
    };
    for (Eigen::Index k = 0; k < modes.frequencies_hz.size(); ++k) {
      Eigen::Index largest = 0;
      const double share = modes.strain_fractions.row(k).maxCoeff(&largest);
      const std::string strain =
          share > 0.0 ? modes.strain_names[static_cast<std::size_t>(largest)] : std::string("—");
      std::printf("%4ld %12.2f  %-14s %8.1f%% %9.1f%% %6.1f%% %7.1f%%   %s %.1f%%\n",
                  static_cast<long>(k), modes.frequencies_hz(k),
                  ToString(modes.labels[static_cast<std::size_t>(k)]),
                  kinetic(k, DofKind::kRotationAxial), kinetic(k, DofKind::kTranslationTransverse),
                  kinetic(k, DofKind::kTranslationAxial), kinetic(k, DofKind::kRotationTilt),
                  strain.c_str(), 100.0 * share);
    }
    for (const std::string& warning : modes.summary.warnings) {
      std::printf("warning: %s\n", warning.c_str());
    }
    return modes.summary.ok() ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ex01_helical_pair_modes: %s\n", e.what());
    return 2;
  }
}
