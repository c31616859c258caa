#include "geardyn/stability_chart_runner.hpp"

#include <atomic>
#include <charconv>
#include <cmath>
#include <memory>
#include <mutex>
#include <numbers>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/analyses/prepared_floquet.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/interrupt.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/region_plot.hpp"

namespace geardyn::app {
namespace {

// Shortest text that reads back as the same double (a valid TOML integer or float).
std::string FormatValue(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof(buf), v);
  return std::string(buf, r.ptr);
}

std::string Override(const std::string& path, double value) {
  return path + "=" + FormatValue(value);
}

std::string AxisText(const char* option, const ChartAxisSpec& a) {
  return std::string(option) + " " + a.path + "=" + FormatValue(a.lo) + ":" + FormatValue(a.hi) +
         ":" + std::to_string(a.num_points);
}

double ParseNumber(const std::string& option, const std::string& text, const std::string& part,
                   const char* what) {
  double v = 0.0;
  const char* end = part.data() + part.size();
  const auto r = std::from_chars(part.data(), end, v);
  if (part.empty() || r.ec != std::errc() || r.ptr != end || !std::isfinite(v)) {
    throw InvalidInput(option + " " + text + ": the " + what + " '" + part +
                       "' is not a finite number");
  }
  return v;
}

// One scene state: its model, the first mesh's frequency and the speed it was built at.
struct Built {
  std::shared_ptr<const SystemModel> model;
  /// Grid rows only: the model prepared for Floquet at any speed (PreparedFloquet).
  std::shared_ptr<const PreparedFloquet> prepared;
  double mesh_hz = 0.0;
  double rpm = 0.0;
  double hz_per_rpm() const { return rpm > 0.0 ? mesh_hz / rpm : 0.0; }
  /// Grid rows only: why the row's scene is invalid (model is null then); "" when valid.
  std::string invalid;
};

class ChartContext {
 public:
  explicit ChartContext(const SceneChartSettings& s) : s_(s) {
    if (s.x.path == kSpeedPath) speed_axis_ = 1;
    if (s.y.path == kSpeedPath) speed_axis_ = 2;
  }

  int speed_axis() const { return speed_axis_; }
  long builds() const { return builds_.load(); }
  long refined() const { return refined_.load(); }

  Built Build(const std::vector<std::string>& extra) const {
    std::vector<std::string> overrides = s_.overrides;
    overrides.insert(overrides.end(), extra.begin(), extra.end());
    const Scene scene = s_.scene_text.empty() ? LoadScene(s_.scene, overrides)
                                              : ParseScene(s_.scene_text, s_.scene, overrides);
    if (scene.meshes.empty() && !scene.oscillator) {
      throw InvalidInput(scene.source + ": the scene has no mesh (a stability chart needs one)");
    }
    SceneSystemOptions system_options;
    system_options.analysis = "stability-chart";  // named if a mass is missing
    system_options.transmission_error = false;    // homogeneous problem: ε is forcing
    Built b;
    b.model = std::make_shared<const SystemModel>(MakeSystemModel(scene, system_options));
    b.mesh_hz = scene.NominalMeshFrequencyHz();  // an oscillator: frequency_ratio [Hz]
    b.rpm = scene.operating_point.speed * 60.0 / (2.0 * std::numbers::pi);
    ++builds_;
    return b;
  }

  // The model of the parameter value (speed on the other axis at its lower end, > 0).
  Built BuildParameter(const ChartAxisSpec& param, double value, const ChartAxisSpec& speed) const {
    return Build({Override(param.path, value), Override(speed.path, speed.lo)});
  }

  void BuildRows() {
    if (speed_axis_ == 0) return;
    const ChartAxisSpec& param = speed_axis_ == 1 ? s_.y : s_.x;
    const ChartAxisSpec& speed = speed_axis_ == 1 ? s_.x : s_.y;
    const ChartAxis axis{param.path, param.lo, param.hi, param.num_points};
    rows_.clear();
    for (int i = 0; i < axis.num_points; ++i) {
      Built b;
      try {
        b = BuildParameter(param, axis.Value(i), speed);
      } catch (const InvalidInput& e) {  // its points are undetermined (Evaluate)
        b.invalid = e.what();
        rows_.push_back(std::move(b));
        continue;
      }
      // Every point of a row is a Floquet solve of this model at another speed: build the
      // frequency-independent part once (prepared_floquet.hpp).
      if (s_.prepare_rows)
        b.prepared = std::make_shared<const PreparedFloquet>(b.model, s_.floquet);
      prepared_rows_ += b.prepared && b.prepared->prepared() ? 1 : 0;
      rows_.push_back(std::move(b));
    }
  }

  long prepared_rows() const { return prepared_rows_; }

  const std::vector<Built>& rows() const { return rows_; }

  // A point whose scene is invalid (an interior value of an axis the scene refuses, e.g. a
  // contact ratio below 1; both ends were checked before) is undetermined, not the end of the
  // chart: the points before and after it are kept. The first reason goes to the warnings.
  ChartPointResult Evaluate(const ChartPoint& p) const {
    try {
      return EvaluateScene(p);
    } catch (const InvalidInput& e) {
      const std::lock_guard<std::mutex> lock(invalid_mutex_);
      if (invalid_points_++ == 0) first_invalid_ = e.what();
      ChartPointResult out;
      out.ok = false;
      return out;
    }
  }

  /// Grid points whose scene was invalid, and the first reason ("" when none).
  long invalid_points() const {
    const std::lock_guard<std::mutex> lock(invalid_mutex_);
    return invalid_points_;
  }
  std::string first_invalid() const {
    const std::lock_guard<std::mutex> lock(invalid_mutex_);
    return first_invalid_;
  }

 private:
  ChartPointResult EvaluateScene(const ChartPoint& p) const {
    double f_m = 0.0;
    std::shared_ptr<const SystemModel> model;
    std::shared_ptr<const PreparedFloquet> prepared;
    if (speed_axis_ == 0) {
      const Built b = Build({Override(s_.x.path, p.x), Override(s_.y.path, p.y)});
      model = b.model;
      f_m = b.mesh_hz;
    } else {
      const bool on_x = speed_axis_ == 1;
      const int index = on_x ? p.iy : p.ix;
      const double rpm = on_x ? p.x : p.y;
      const Built b =
          index >= 0 ? rows_[index]
                     : BuildParameter(on_x ? s_.y : s_.x, on_x ? p.y : p.x, on_x ? s_.x : s_.y);
      if (!b.invalid.empty()) throw InvalidInput(b.invalid);
      model = b.model;
      prepared = b.prepared;
      f_m = b.hz_per_rpm() * rpm;
    }
    FloquetOptions options = s_.floquet;
    options.mesh_frequency_hz = f_m;
    options.magnus_measured_order = s_.measured_order;  // the screening run (see the @file)
    options.list_undamped_modes = false;  // the chart reads max|λ| and the verdict only
    auto floquet = [&](const FloquetOptions& o) {
      return prepared ? prepared->Compute(o) : ComputeFloquet(*model, o);
    };
    FloquetResult r = floquet(options);
    // A growth above the threshold but within twice the estimate could be the screening
    // tolerance's error: resolve it at the verdict tolerance (see the @file).
    const double growth = r.max_abs_multiplier - 1.0 - s_.chart.instability_threshold;
    if (options.tolerance > s_.verdict_tolerance && growth > 0.0 &&
        growth <= 2.0 * r.summary.error_estimate) {
      options.tolerance = s_.verdict_tolerance;
      r = floquet(options);
      ++refined_;
    }
    ChartPointResult out;
    out.max_abs_multiplier = r.max_abs_multiplier;
    out.error_estimate = r.summary.error_estimate;
    out.mesh_frequency_hz = f_m;
    // Only a point with a verdict is charted: a missed tolerance still counts when the point
    // is unstable beyond its estimate (FloquetVerdict); undetermined points are counted apart.
    out.ok = r.verdict != FloquetVerdict::kUndetermined;
    return out;
  }

  const SceneChartSettings& s_;
  int speed_axis_ = 0;  // 0 none, 1 x, 2 y
  std::vector<Built> rows_;
  long prepared_rows_ = 0;
  mutable std::atomic<long> builds_{0};
  mutable std::atomic<long> refined_{0};
  mutable std::mutex invalid_mutex_;
  mutable long invalid_points_ = 0;
  mutable std::string first_invalid_;
};

std::vector<double> NaturalFrequencies(const SystemModel& model) {
  ModalOptions options;
  options.compute_energy_fractions = false;
  options.compute_damping_ratios = false;  // frequencies only: no vectors even when C ≠ 0
  const ModalResult modes = ComputeModes(model, options);
  return {modes.frequencies_hz.data(), modes.frequencies_hz.data() + modes.frequencies_hz.size()};
}

}  // namespace

ChartAxisSpec ParseChartAxis(const std::string& option, const std::string& text) {
  const std::size_t eq = text.rfind('=');
  if (eq == std::string::npos || eq == 0) {
    throw InvalidInput(option + " " + text + ": expected PATH=LO:HI:N, e.g. " + option + " " +
                       kSpeedPath + "=500:3000:50");
  }
  ChartAxisSpec a;
  a.path = text.substr(0, eq);
  const std::string range = text.substr(eq + 1);
  const std::size_t c1 = range.find(':');
  const std::size_t c2 = c1 == std::string::npos ? c1 : range.find(':', c1 + 1);
  if (c2 == std::string::npos || range.find(':', c2 + 1) != std::string::npos) {
    throw InvalidInput(option + " " + text + ": expected PATH=LO:HI:N (three fields after '=')");
  }
  a.lo = ParseNumber(option, text, range.substr(0, c1), "lower bound");
  a.hi = ParseNumber(option, text, range.substr(c1 + 1, c2 - c1 - 1), "upper bound");
  const std::string n = range.substr(c2 + 1);
  int count = 0;
  const auto r = std::from_chars(n.data(), n.data() + n.size(), count);
  if (n.empty() || r.ec != std::errc() || r.ptr != n.data() + n.size()) {
    throw InvalidInput(option + " " + text + ": the number of points '" + n +
                       "' is not an integer");
  }
  a.num_points = count;
  if (count < 2) {
    throw InvalidInput(option + " " + text + ": the number of points must be at least 2, got " + n);
  }
  if (!(a.lo < a.hi)) {
    throw InvalidInput(option + " " + text + ": the lower bound must be below the upper bound");
  }
  if (a.path == kSpeedPath && !(a.lo > 0.0)) {
    throw InvalidInput(option + " " + text +
                       ": the speed must be > 0 at every point (the mesh frequency must be "
                       "positive)");
  }
  return a;
}

SceneChart ComputeSceneStabilityChart(const SceneChartSettings& settings) {
  const ChartAxisSpec& x = settings.x;
  const ChartAxisSpec& y = settings.y;
  if (x.path == y.path) {
    throw InvalidInput("--x and --y name the same scene path '" + x.path + "'");
  }
  {
    // Sizes first: a huge grid is refused before any model is built.
    const ChartAxis ax{x.path, x.lo, x.hi, x.num_points};
    const ChartAxis ay{y.path, y.lo, y.hi, y.num_points};
    std::string why;
    if (!ax.IsValid("--x", &why) || !ay.IsValid("--y", &why) || !IsValidChartGrid(ax, ay, &why)) {
      throw InvalidInput(why);
    }
  }
  ChartContext context(settings);

  // Both ends of both axes must give a valid scene; name the axis whose value is rejected.
  Built nominal;
  for (const bool upper : {false, true}) {
    const std::string ox = Override(x.path, upper ? x.hi : x.lo);
    const std::string oy = Override(y.path, upper ? y.hi : y.lo);
    try {
      const Built b = context.Build({ox, oy});
      if (!upper) nominal = b;
    } catch (const SceneError& e) {
      const std::string& spec = e.override_spec();
      if (spec == ox) throw InvalidInput(AxisText("--x", x) + ": " + e.what());
      if (spec == oy) throw InvalidInput(AxisText("--y", y) + ": " + e.what());
      throw;
    }
  }
  if (!(nominal.mesh_hz > 0.0)) {
    throw InvalidInput(settings.scene +
                       ": the mesh frequency is 0 at the lower ends of the axes (speed 0 rpm); "
                       "set operating_point.speed_rpm > 0 or chart over it");
  }
  context.BuildRows();

  SceneChart out;
  out.speed_axis = context.speed_axis() == 1 ? "x" : context.speed_axis() == 2 ? "y" : "";
  out.mesh_hz_per_rpm = nominal.hz_per_rpm();
  out.natural_frequencies_hz = NaturalFrequencies(*nominal.model);

  StabilityChartOptions options = settings.chart;
  options.cancel = CancelFlag();
  options.first_mode_index = 0;  // mode numbers as `geardyn modes` prints them
  options.natural_frequencies_hz.clear();
  if (context.speed_axis() == 1) {             // a model per y row: its own frequencies
    for (const Built& row : context.rows()) {  // an invalid row: no labels
      options.natural_frequencies_hz.push_back(row.model ? NaturalFrequencies(*row.model)
                                                         : std::vector<double>{});
    }
  } else {
    options.natural_frequencies_hz.push_back(out.natural_frequencies_hz);
    if (context.speed_axis() == 0) {
      out.warnings.push_back(
          "no axis is operating_point.speed_rpm: every point builds its own model, and the "
          "region labels use the natural frequencies at the axes' lower ends");
    } else {
      out.warnings.push_back(
          "the model varies along x: the region labels use the natural frequencies at the "
          "lower end of x");
    }
  }

  const ChartAxis ax{x.path, x.lo, x.hi, x.num_points};
  const ChartAxis ay{y.path, y.lo, y.hi, y.num_points};
  const ChartContext& shared = context;
  out.chart = ComputeStabilityChart(
      ax, ay,
      [&shared]() -> ChartEvaluator {
        return [&shared](const ChartPoint& p) { return shared.Evaluate(p); };
      },
      options);
  for (const std::string& w : out.chart.summary.warnings) out.warnings.push_back(w);
  if (context.invalid_points() > 0) {
    out.warnings.push_back(
        std::to_string(context.invalid_points()) +
        " grid points have an invalid scene (undetermined), the first: " + context.first_invalid());
  }
  out.model_builds = context.builds();
  out.refined_points = context.refined();
  out.prepared_rows = context.prepared_rows();
  return out;
}

RegionPlotSpec MakeRegionPlotGrid(const StabilityChartResult& c, const std::string& title) {
  RegionPlotSpec spec;
  spec.title = title;
  spec.x_label = c.x_axis.name;
  spec.y_label = c.y_axis.name;
  for (int i = 0; i < c.x_axis.num_points; ++i) spec.x_values.push_back(c.x_axis.Value(i));
  for (int i = 0; i < c.y_axis.num_points; ++i) spec.y_values.push_back(c.y_axis.Value(i));
  spec.max_abs_multiplier = c.max_abs_multiplier;
  spec.stable = c.stable;
  spec.ok = c.ok;
  return spec;
}

}  // namespace geardyn::app
