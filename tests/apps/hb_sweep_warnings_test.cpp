// `geardyn hb` over a sweep lists each distinct warning once: the per-point warnings of the
// library's points (each point's own undamped-mode check, a different path from the sweep's
// merge) give, per undamped mode, the mesh frequencies where it dominated; the report must hold
// exactly one warning per such mode, naming that range and count, instead of one per point.
#include <gtest/gtest.h>

#include <iomanip>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "support/cli_run.hpp"

namespace geardyn::app {
namespace {

using test::RunJson;

// The text every undamped-mode warning carries after its share.
constexpr const char* kUndampedText = " % of the alternating response (mass-weighted) is in an";

// A frequency as the warnings print it: 6 significant digits.
std::string Hz(double x) {
  std::ostringstream os;
  os << std::setprecision(6) << x;
  return os.str();
}

// The built-in rig without system damping: its bearing modes are undamped, and near 3 290 Hz
// (docs/design.md, issue 12) such a mode dominates the alternating response.
TEST(HbCommandTest, SweepListsEachWarningOnce) {
  const std::vector<double> freqs = {3100.0, 3150.0, 3200.0, 3250.0, 3300.0,
                                     3350.0, 3400.0, 3450.0, 3500.0};
  const nlohmann::json report =
      RunJson({"hb", "builtin:kahraman-blankenship-rig", "--mesh-frequency", "3100:3500:9",
               "--harmonics", "8", "--stability", "none"});
  ASSERT_EQ(report["points"].size(), freqs.size());

  // Per mode (the warning text after the share), the frequencies of the points that warned.
  const SystemModel model = MakeSystemModel(LoadScene("builtin:kahraman-blankenship-rig"));
  HbOptions options;
  options.harmonics = 8;
  const HbSweepResult sweep = SweepHarmonicBalance(model, freqs, options);
  std::map<std::string, std::vector<double>> by_mode;
  for (const HbResult& point : sweep.points) {
    for (const std::string& w : point.summary.warnings) {
      const std::size_t at = w.find(kUndampedText);
      if (at != std::string::npos) by_mode[w.substr(at)].push_back(point.mesh_frequency_hz);
    }
  }
  ASSERT_FALSE(by_mode.empty()) << "the case does not exercise the undamped-mode warning";
  bool repeated = false;
  for (const auto& [mode, at] : by_mode) repeated = repeated || at.size() > 1;
  ASSERT_TRUE(repeated) << "no undamped-mode warning at more than one point";

  std::vector<std::string> warnings;
  for (const auto& w : report["warnings"]) warnings.push_back(w.get<std::string>());
  int undamped_warnings = 0;
  for (const std::string& w : warnings) {
    if (w.find(kUndampedText) != std::string::npos) ++undamped_warnings;
  }
  EXPECT_EQ(undamped_warnings, static_cast<int>(by_mode.size()));
  for (const auto& [mode, at] : by_mode) {
    int found = 0;
    for (const std::string& w : warnings) {
      if (w.find(mode) == std::string::npos) continue;
      ++found;
      if (at.size() > 1) {
        EXPECT_NE(w.find("f_m = " + Hz(at.front()) + " … " + Hz(at.back()) + " Hz (" +
                         std::to_string(at.size()) + " of " + std::to_string(freqs.size()) +
                         " points): up to "),
                  std::string::npos)
            << w;
      } else {
        EXPECT_EQ(w.rfind("harmonic balance at " + Hz(at.front()) + " Hz: ", 0), 0u) << w;
      }
    }
    EXPECT_EQ(found, 1) << mode;
  }
}

// The planetary's repeated (degenerate) modes give two warnings with the same text at one
// point; the merged count is of points, so "k of N points" has k = the number of distinct points
// that warned about that mode (truth: the library's own points), never k > N.
TEST(HbCommandTest, RepeatedModesAreCountedOncePerPoint) {
  const std::vector<double> freqs = {100.0, 200.0, 300.0, 400.0, 500.0, 600.0, 700.0, 800.0};
  const nlohmann::json report = RunJson({"hb", "builtin:planetary-lin-parker", "--mesh-frequency",
                                         "100:800:8", "--harmonics", "8", "--stability", "none"});
  ASSERT_EQ(report["points"].size(), freqs.size());
  const SystemModel model = MakeSystemModel(LoadScene("builtin:planetary-lin-parker"));
  HbOptions options;
  options.harmonics = 8;
  const HbSweepResult sweep = SweepHarmonicBalance(model, freqs, options);
  std::map<std::string, std::set<double>> by_mode;
  bool twice_at_a_point = false;
  for (const HbResult& point : sweep.points) {
    std::map<std::string, int> here;
    for (const std::string& w : point.summary.warnings) {
      const std::size_t at = w.find(kUndampedText);
      if (at == std::string::npos) continue;
      by_mode[w.substr(at)].insert(point.mesh_frequency_hz);
      twice_at_a_point = twice_at_a_point || ++here[w.substr(at)] > 1;
    }
  }
  ASSERT_TRUE(twice_at_a_point) << "the case does not exercise a repeated mode";
  for (const auto& w : report["warnings"]) {
    const std::string text = w.get<std::string>();
    for (const auto& [mode, at] : by_mode) {
      if (text.find(mode) == std::string::npos || at.size() < 2) continue;
      EXPECT_NE(text.find("(" + std::to_string(at.size()) + " of " + std::to_string(freqs.size()) +
                          " points)"),
                std::string::npos)
          << text;
    }
  }
}

}  // namespace
}  // namespace geardyn::app
