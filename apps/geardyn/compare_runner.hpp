/// @file
/// @brief `geardyn compare`: one scene at several model levels, every requested analysis per level,
/// and the differences of each level to the reference level (issue 15; spec 01 §5; B–S §5.3).
///
/// **Analyses per level** (each exactly what the single-analysis command computes):
/// * modes — ComputeModes of the mean system with shapes; matched to the reference's modes by
///   mass-weighted MAC (mode_matching.hpp): relative frequency difference and MAC per reference
///   mode; reference modes without a match (MAC < threshold) are *absent*, not dropped.
/// * floquet — ComputeFloquet at the operating point: max|λ| and the three-valued verdict.
/// * DTE — RMS and peak-to-peak DTE of the compared mesh over the mesh-frequency grid:
///   * linear levels: SweepHarmonicBalance (`geardyn hb --linear`);
///   * slices: TraceSystemNonlinearHb over the grid's range (`geardyn hb`), read on the grid as
///     the two branches a slow up-sweep and down-sweep follow (ResampleNhbBranches);
///   * with `simulate` (and for the contact level, which has no harmonic balance): SimulateSweep
///     up and down (`geardyn simulate --sweep both`).
///   A level's DTE comes from its harmonic balance when `hb` is requested and the level has one,
///   else from the time domain when `simulate` is requested.
///   **Quantity.** The loaded transmission error δ_η = g·q along the tooth normal (Kim et al.
///   2015 Eq. 14; what an encoder measures), the same for every level: the linear levels' DTE
///   δ_η − ε_η (probes.hpp) gets ε_η back, since the slice and contact levels carry the tooth
///   modifications and errors as separations, not as ε. Without modifications or errors ε = 0
///   and δ_η is the DTE of `geardyn hb`.
/// * **Differences** to the reference level: per grid frequency d = (RMS_level − RMS_ref) /
///   max RMS_ref (a fraction of the reference's peak, so that anti-resonances do not blow it up),
///   up and down branch; summarised by max |d|, its frequency and where it sits (a resonance peak,
///   a jump / multi-valued range, off resonance), the RMS of d, and the resonance-peak shift.
///
/// **Reference.** The most detailed requested level that ran the analysis (CompareLevels order),
/// or the user's. **Verdicts** are three-valued: a level whose analysis (or the reference's)
/// did not succeed gets "undetermined", never "agrees".
#pragma once

#include <limits>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "geardyn/analyses/floquet.hpp"
#include "geardyn/analyses/modal.hpp"
#include "geardyn/analyses/mode_matching.hpp"
#include "geardyn/analyses/stability_chart.hpp"
#include "geardyn/common/eigen_types.hpp"
#include "geardyn/common/summary.hpp"
#include "geardyn/compare_levels.hpp"
#include "geardyn/models/scene/scene.hpp"

namespace geardyn::app {

/// The settings of one comparison (the command line's, validated by ValidateCompareSettings).
struct CompareSettings {
  std::vector<std::string> levels;        ///< in CompareLevels order; empty: the defaults
  bool levels_given = false;              ///< --levels given: an unbuildable level is an error
  std::vector<CompareAnalysis> analyses;  ///< what to run
  std::string reference;                  ///< --reference (empty: the most detailed)
  std::string mesh;                       ///< the compared mesh (empty: the first)
  std::string mesh_frequency;             ///< "lo:hi:n" or "f" [Hz] (empty: the default grid)
  int num_modes = 12;                     ///< reference modes compared
  double mac_threshold = 0.8;             ///< least MAC of a match
  double frequency_tolerance = 0.01;      ///< |Δf/f| accepted as agreement [-]
  double dte_tolerance = 0.05;            ///< |d| accepted as agreement [-] (of the ref peak)
  int nonlinear_harmonics = 24;           ///< H of the nonlinear HB
  /// Nonlinear HB: frequencies where Newton starts from scaled contact guesses to find branches
  /// off the traced curve (SystemNhbOptions; `geardyn hb --branch-search`), 0: off.
  int branch_search = 8;
  double simulate_tolerance = 1e-6;  ///< local relative error of the time integration
  int max_periods = 3000;            ///< time domain: periods before not_converged
  double steady_tolerance = 1e-6;    ///< time domain: relative period-to-period change of steady
  int threads = 0;                   ///< time domain: OpenMP threads (0: default)
  bool progress = false;             ///< progress lines on the error stream
  /// With the contact level: the other levels take the contact model's mean mesh stiffness and
  /// its law's damping at the mean load (overlay_match.hpp), so that they model the same teeth
  /// (ISO 6336's stiffness and the scene's mesh damping otherwise).
  bool match_contact = true;
  /// Stability charts per level (with floquet): "path=lo:hi:n" of both axes, as
  /// `geardyn stability-chart --x/--y`; empty: none. They need the scene's path and overrides
  /// (the chart reloads the scene at every axis value).
  std::string chart_x, chart_y;
  std::string scene_path;  ///< file or builtin:NAME (charts)
  /// The scene's TOML text when it was not read from scene_path (the Python package's text and
  /// dict scenes); empty: LoadScene(scene_path).
  std::string scene_text;
  std::vector<std::string> overrides;  ///< --set of the scene (charts)
};

/// @throws InvalidInput naming the option on a bad value.
void ValidateCompareSettings(const CompareSettings& settings);

/// DTE of one level over the grid (one mesh) [m]; NaN where a branch has no stable solution.
struct LevelDte {
  std::string source;  ///< "linear hb", "nonlinear hb", "simulate"
  std::vector<double> rms_up, rms_down, peak_to_peak_up, peak_to_peak_down;
  /// The traced nonlinear-HB curve (empty otherwise): frequency [Hz], RMS [m], verdict
  /// (1 stable, 0 unstable, −1 undetermined) and segment per point.
  std::vector<double> curve_hz, curve_rms;
  std::vector<int> curve_stable, curve_segment;
  std::vector<double> jumps_hz;  ///< jump frequencies of the traced nonlinear HB (empty otherwise)
  Summary summary;
  double wall_time_s = 0.0;
  /// True when the up and down branches differ somewhere by more than 1 % of the peak.
  bool multivalued = false;
};

/// One level's runs.
struct LevelRun {
  std::string level;
  std::map<CompareAnalysis, std::string> skipped;  ///< reason per analysis not run
  std::optional<ModalResult> modes;
  double modes_time_s = 0.0;
  std::optional<FloquetResult> floquet;
  double floquet_time_s = 0.0;
  std::optional<LevelDte> dte;
  /// The stability chart of the level (settings.chart_x/y), its wall time and why it is missing.
  std::optional<StabilityChartResult> chart;
  double chart_time_s = 0.0;
  std::string chart_skipped;
  std::vector<std::string> warnings;
  int num_dofs = 0;
  SparseMatrix mass;  ///< M of the level's system (the MAC's weight) [kg, kg·m, kg·m²]
};

/// Differences of one level's DTE to the reference's.
struct DteDifference {
  std::vector<double> up, down;  ///< d per grid frequency [-] (NaN where either is missing)
  double max_abs = 0.0;          ///< max |d| [-] (NaN when nothing is comparable)
  double max_at_hz = 0.0;        ///< where [Hz]
  std::string max_where;         ///< "resonance", "jump", "off resonance"
  double rms = 0.0;              ///< RMS of d over both branches [-]
  double peak_hz = 0.0, reference_peak_hz = 0.0;  ///< frequency of the largest RMS [Hz]
  double peak_ratio = 0.0;  ///< largest RMS of the level / of the reference [-]
  int missing = 0;          ///< grid points compared on one side only
  /// Frequency ranges [Hz] where |d| > tolerance, merged over neighbouring grid points.
  std::vector<std::pair<double, double>> disagree_ranges;
};

/// One level against the reference.
struct LevelComparison {
  std::string level;
  std::optional<ModeMatching> modes;
  /// max |Δf/f| of the matched modes whose reference type is in the plane of the gears
  /// (rotational, translational) and out of it (axial, rocking) [-] (0 when none; NaN without
  /// modes): the 4-DOF and torsional reductions act on these differently.
  double modes_max_in_plane = std::numeric_limits<double>::quiet_NaN();
  double modes_max_out_of_plane = std::numeric_limits<double>::quiet_NaN();
  std::optional<double> floquet_difference;  ///< max|λ| − reference's
  std::optional<DteDifference> dte;
  /// Chart: the fraction of grid points where both have a verdict and it is the reference's
  /// (NaN without charts), and the number of points compared.
  double chart_agreement = std::numeric_limits<double>::quiet_NaN();
  int chart_points = 0;
  /// Per analysis: "agrees", "differs", "undetermined", "reference", "skipped".
  std::map<CompareAnalysis, std::string> verdict;
  std::vector<std::string> notes;  ///< the text verdict, one line each
};

/// Everything a comparison produced.
struct CompareResult {
  std::string scene;
  std::string mesh;  ///< the compared mesh
  /// An oscillator scene (Scene::oscillator): the DTE is the dimensionless x, not metres.
  bool dimensionless = false;
  double operating_mesh_frequency_hz = 0.0;
  std::vector<double> frequencies_hz;                ///< the DTE grid
  std::vector<LevelRun> runs;                        ///< in level order
  std::map<CompareAnalysis, std::string> reference;  ///< per analysis ("" when none ran)
  std::vector<LevelComparison> comparisons;          ///< in level order
  std::vector<std::string> warnings;
  std::vector<std::string> notes;  ///< what the comparison did to the data (contact matching)
  CompareSettings settings;
  double wall_time_s = 0.0;
  bool ok = true;  ///< every run analysis succeeded
};

/// @brief Runs the comparison (see the @file).
/// @param[out] progress progress lines when settings.progress (may be null).
/// @throws InvalidInput on bad settings, an explicitly requested level the scene cannot build,
///   or a reference that did not run.
CompareResult RunCompare(const Scene& scene, const CompareSettings& settings,
                         std::ostream* progress = nullptr);

/// @brief The up- and down-sweep branches of a traced nonlinear-HB curve on a grid: at each grid
/// frequency the stable intersections of the curve (segments between consecutive points of one
/// trace segment, both not unstable, interpolated linearly in f); a sweep starts on the smallest
/// RMS and then keeps to the intersection nearest its previous value (it jumps only where its
/// branch ends). NaN where no stable solution crosses the frequency.
/// @param[in] hz, rms, stable, segment the curve in arclength order (same sizes).
/// @param[in] grid ascending frequencies [Hz].
/// @param[out] up, down RMS per grid frequency; @param[out] up_p2p, down_p2p from `p2p`.
void ResampleNhbBranches(const std::vector<double>& hz, const std::vector<double>& rms,
                         const std::vector<double>& p2p, const std::vector<int>& stable,
                         const std::vector<int>& segment, const std::vector<double>& grid,
                         std::vector<double>* up, std::vector<double>* down,
                         std::vector<double>* up_p2p, std::vector<double>* down_p2p);

/// @brief d = (level − reference)/peak per grid point and its summary (see DteDifference).
DteDifference CalcDteDifference(const LevelDte& level, const LevelDte& reference,
                                const std::vector<double>& grid, double tolerance);

}  // namespace geardyn::app
