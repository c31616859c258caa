/// @file
/// @brief The quasi-periodic path of `geardyn hb` (issue 18): a scene whose meshes run at several
/// frequencies (a planetary stage with a parallel stage) is solved on the torus of its mesh
/// frequencies by SolveQuasiPeriodicHb (quasi_periodic_hb.hpp), linear model only.
#pragma once

#include <string>
#include <vector>

#include "geardyn/analysis_runs.hpp"
#include "geardyn/models/system/scene_system.hpp"

namespace geardyn::app {

/// True when some mesh of `model` runs at another frequency than the first (phase ratio ≠ 1).
bool HasSeveralMeshFrequencies(const SystemModel& model);

/// @brief The quasi-periodic linear HB at every listed mesh frequency (of the first mesh).
/// --harmonics H is the total order (|κ|_1 ≤ H); without it H = 8, 16, … until the RMS DTE of
/// every mesh changes by at most --tolerance (relative to the largest) from H/2 to H. Files
/// hb.json, hb.csv and hb_rms_dte.svg as the periodic path; the report adds "quasi_periodic"
/// (the bases) and per point and mesh the largest DTE lines. No Floquet verdicts: the stability
/// of a quasi-periodic LTV system is not available yet, and the report ("stability": "none",
/// "stability_note") and a warning say so — the points are drawn and listed as unverified.
/// @throws InvalidInput on an H over the memory limit (exit code 2).
HbRun RunQuasiPeriodicHb(const HbRunSettings& opts, const Scene& scene, const SceneSystem& built,
                         const std::vector<double>& frequencies, const std::string& out_dir,
                         const ProgressLine& progress);

}  // namespace geardyn::app
