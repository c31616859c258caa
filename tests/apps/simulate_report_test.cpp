// simulate_report.hpp's sweep CSV: a point without values (a failed run) has empty cells, never
// "nan". Truth: the CSV convention of the JSON report (null for no value) — a failed point that
// integrated no period has no RMS, p-p, mean DTE, loss fraction nor energy balance.
#include "geardyn/simulate_report.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

namespace geardyn::app {
namespace {

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(SimulateReportTest, FailedSweepPointHasEmptyCellsNotNan) {
  SimulatePoint ok;
  ok.torque_nm = 100.0;
  ok.branch = "up";
  ok.point.mesh_frequency_hz = 1000.0;
  ok.point.rms_dte = {1e-6};
  ok.point.peak_to_peak_dte = {3e-6};
  ok.point.mean_dte = {2e-6};
  ok.point.contact_loss_fraction = {0.0};
  ok.point.max_energy_error = 1e-7;
  SimulatePoint failed;
  failed.torque_nm = 100.0;
  failed.branch = "up";
  failed.point.mesh_frequency_hz = 1100.0;
  failed.point.status = Status::kNotConverged;
  failed.point.max_energy_error = std::nan("");  // no integrated period (ToSweepPoint)
  const std::vector<std::string> lines = Lines(FormatSimulateSweepCsv({"m"}, {ok, failed}));
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[1], "100,up,1000,success,undetermined,0,1e-07,1e-06,3e-06,2e-06,0");
  EXPECT_EQ(lines[2], "100,up,1100,not_converged,undetermined,0,,,,,");
  EXPECT_EQ(lines[2].find("nan"), std::string::npos);
}

}  // namespace
}  // namespace geardyn::app
