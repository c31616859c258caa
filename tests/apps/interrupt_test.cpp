/// @file
/// @brief Nothing lost (issue 16): an interrupted run (SIGINT/SIGTERM) keeps the points computed
/// before it, writes them marked as partial and exits with 130; result files are written
/// atomically (no half file, no temporary left behind). The truth of each check: the same run
/// uninterrupted (its first points must be the interrupted run's points, bit for bit) and the
/// formats' own parsers (a partial JSON still parses; a partial CSV reads with comment = '#').
#include "geardyn/interrupt.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <streambuf>
#include <string>
#include <utility>
#include <vector>

#include "geardyn/analyses/stability_chart.hpp"
#include "geardyn/cli.hpp"
#include "geardyn/output_files.hpp"

namespace geardyn::app {
namespace {

std::filesystem::path OutDir(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::path(GEARDYN_BINARY_DIR) / "tests" / "interrupt_test_out" / name;
  std::filesystem::remove_all(dir);
  return dir;
}

std::string ReadText(const std::filesystem::path& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// Data rows of a CSV: lines that are neither comments nor the header.
std::vector<std::string> CsvRows(const std::string& text) {
  std::vector<std::string> rows;
  std::istringstream in(text);
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      header = false;
      continue;
    }
    rows.push_back(line);
  }
  return rows;
}

// An error stream that raises `signal_number` once its text contains `trigger`: with --progress,
// a signal that arrives in the middle of a sweep, deterministically.
class SignalOnText : public std::streambuf {
 public:
  SignalOnText(int signal_number, std::string trigger)
      : signal_(signal_number), trigger_(std::move(trigger)) {}

 protected:
  int overflow(int c) override {
    if (c != traits_type::eof()) Append(std::string(1, static_cast<char>(c)));
    return c;
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    Append(std::string(s, static_cast<std::size_t>(n)));
    return n;
  }

 private:
  void Append(const std::string& s) {
    text_ += s;
    if (!raised_ && text_.find(trigger_) != std::string::npos) {
      raised_ = true;
      std::raise(signal_);
    }
  }
  int signal_;
  std::string trigger_;
  std::string text_;
  bool raised_ = false;
};

TEST(OutputFiles, PartialMarksKeepEveryFormatReadable) {
  const nlohmann::json marked =
      nlohmann::json::parse(MarkPartial("a.json", "{\n  \"status\": \"interrupted\"\n}\n"));
  EXPECT_EQ(marked["partial"], true);
  EXPECT_EQ(marked["status"], "interrupted");
  EXPECT_EQ(nlohmann::json::parse(MarkPartial("b.json", "{}"))["partial"], true);

  const std::string csv = MarkPartial("a.csv", "f_hz,rms\n1,2\n");
  EXPECT_EQ(csv.rfind("# partial", 0), 0u) << csv;
  EXPECT_EQ(CsvRows(csv), std::vector<std::string>{"1,2"});

  const std::string svg = MarkPartial("a.svg", "<?xml version=\"1.0\"?>\n<svg></svg>\n");
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u) << svg;  // nothing may precede the declaration
  EXPECT_NE(svg.find("<!-- partial"), std::string::npos) << svg;
}

TEST(OutputFiles, WritesReplaceAtomicallyAndLeaveNoTemporary) {
  const std::filesystem::path dir = OutDir("atomic");
  WriteOutputFile(dir, "r.csv", "old\n");
  WriteOutputFile(dir, "r.csv", "new\n");
  EXPECT_EQ(ReadText(dir / "r.csv"), "new\n");
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    ++files;
    EXPECT_EQ(entry.path().filename(), "r.csv");
  }
  EXPECT_EQ(files, 1);
}

// SIGINT during `geardyn hb`: the sweep stops between points; the points kept are those of the
// uninterrupted sweep, written marked as partial, exit code 130.
TEST(Interrupt, LinearHbSweepKeepsThePointsSolvedBeforeTheCancel) {
  const int total = 12;
  std::ostringstream out, err;
  // The model of a built-in scene, through the command (its JSON lists every point).
  const std::filesystem::path full_dir = OutDir("hb_full");
  const std::vector<std::string> args = {"hb",
                                         "builtin:kahraman-blankenship-rig",
                                         "--mesh-frequency",
                                         "1000:2100:12",
                                         "--stability",
                                         "none",
                                         "--progress",
                                         "--set",
                                         "mesh.pinion-wheel.damping_ratio=0.05"};
  std::vector<std::string> full_args = args;
  full_args.insert(full_args.end(), {"--out", full_dir.string()});
  ASSERT_EQ(RunCli(full_args, out, err), kExitOk) << err.str();
  EXPECT_FALSE(Interrupted());
  const std::vector<std::string> full_rows = CsvRows(ReadText(full_dir / "hb.csv"));
  ASSERT_EQ(full_rows.size(), static_cast<std::size_t>(total));

  // The same run, SIGINT once the progress says 3 points are done (a line per point).
  const std::filesystem::path dir = OutDir("hb_interrupted");
  std::vector<std::string> cut_args = args;
  cut_args.insert(cut_args.end(), {"--out", dir.string()});
  SignalOnText buffer(SIGINT, "3/12 mesh frequencies\n");
  std::ostream signalling(&buffer);
  std::ostringstream cut_out;
  EXPECT_EQ(RunCli(cut_args, cut_out, signalling), kExitInterrupted);
  // The handler is gone after the run: the previous (default) disposition is back.
  void (*handler)(int) = std::signal(SIGINT, SIG_DFL);
  EXPECT_EQ(handler, SIG_DFL);

  const std::string csv = ReadText(dir / "hb.csv");
  EXPECT_EQ(csv.rfind("# partial", 0), 0u) << csv.substr(0, 200);
  const std::vector<std::string> rows = CsvRows(csv);
  ASSERT_EQ(rows.size(), 3u);  // the sweep stops before its fourth point
  for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(rows[i], full_rows[i]) << i;
  const nlohmann::json report = nlohmann::json::parse(ReadText(dir / "hb.json"));
  EXPECT_EQ(report["partial"], true);
  EXPECT_EQ(report["status"], "interrupted");
  EXPECT_TRUE(std::filesystem::exists(dir / "hb_rms_dte.svg"));
}

// The chart: a cancel during the grid; the points computed are kept, the rest undetermined, and
// no transition curve is traced from an incomplete grid.
TEST(Interrupt, StabilityChartGridStopsAndKeepsItsPoints) {
  std::atomic<bool> cancel{false};
  const ChartEvaluatorFactory factory = [&cancel]() -> ChartEvaluator {
    return [&cancel](const ChartPoint& p) -> ChartPointResult {
      if (p.ix == 2 && p.iy == 0) cancel.store(true);  // the third point asks to stop
      ChartPointResult r;
      r.ok = true;
      r.max_abs_multiplier = 0.5;
      r.mesh_frequency_hz = p.x;
      return r;
    };
  };
  StabilityChartOptions options;
  options.num_threads = 1;
  options.cancel = &cancel;
  const StabilityChartResult chart =
      ComputeStabilityChart({"f", 1.0, 2.0, 5}, {"e", 0.0, 1.0, 4}, factory, options);
  EXPECT_EQ(chart.summary.status, Status::kInterrupted);
  EXPECT_NE(chart.summary.message.find("3 of 20"), std::string::npos) << chart.summary.message;
  for (long i = 0; i < 20; ++i) EXPECT_EQ(chart.ok[i], i < 3 ? 1 : 0) << i;
  EXPECT_TRUE(chart.curves.empty());
}

}  // namespace
}  // namespace geardyn::app
