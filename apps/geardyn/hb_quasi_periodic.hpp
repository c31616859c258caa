/// @file
/// @brief The quasi-periodic path of `geardyn hb` (issue 18): a scene whose meshes run at several
/// frequencies (a planetary stage with a parallel stage) is solved on the torus of its mesh
/// frequencies by SolveQuasiPeriodicHb (quasi_periodic_hb.hpp) or, with slice meshes,
/// SolveNonlinearQuasiPeriodicHb (nonlinear_quasi_periodic_hb.hpp).
#pragma once

#include <string>
#include <vector>

#include "geardyn/analysis_runs.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/system/common_period.hpp"  // HasSeveralMeshFrequencies

namespace geardyn::app {

/// @brief The quasi-periodic linear HB at every listed mesh frequency (of the first mesh).
/// --harmonics H is the total order (|κ|_1 ≤ H); without it H = 8, 16, … until the RMS DTE of
/// every mesh changes by at most --tolerance (default 2e-2) relative to the largest from H/2 to
/// H, stopping with tolerance_not_met before an order whose factors need over 0.5 GB. Files
/// hb.json, hb.csv and hb_rms_dte.svg as the periodic path; the report adds "quasi_periodic"
/// (the bases) and per point and mesh the largest DTE lines. No Floquet verdicts: the monodromy
/// over the common period (`geardyn floquet`, 40 mesh cycles on the two-stage example) costs
/// minutes per frequency on a gearbox, and the report ("stability": "none", "stability_note")
/// and a warning say so — the points are drawn and listed as unverified.
/// @throws InvalidInput on an H over the memory limit (exit code 2).
/// With `nonlinear` (slice meshes, issue 18): SolveNonlinearQuasiPeriodicHb with contact loss
/// and back-flank contact instead, each frequency's Newton starting from the previous
/// frequency's solution at the same H (a sequential sweep: no arclength continuation, so at a
/// fold the sweep jumps as a slow physical sweep would, and an unstable branch is not traced);
/// files nhb.json, nhb.csv (plus per mesh contact_loss_fraction, min_force_n, max_force_n) and
/// nhb_rms_dte.svg, and per point and mesh the contact in the JSON.
HbRun RunQuasiPeriodicHb(const HbRunSettings& opts, const Scene& scene, const SceneSystem& built,
                         const std::vector<double>& frequencies, const std::string& out_dir,
                         const ProgressLine& progress, bool nonlinear = false);

}  // namespace geardyn::app
