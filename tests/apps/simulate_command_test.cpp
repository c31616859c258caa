// `geardyn simulate`: bad options exit 2 naming the option and its bound; the default run (one
// speed to steady state) of an LTV scene and of the slice rig equals harmonic balance at the same
// mesh frequency (an independent, frequency-domain method); a stepped sweep writes up and down
// branches, which agree where the steady state is unique (LTV); a run that fails (a tiny
// --max-periods) keeps its files.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "geardyn/cli.hpp"
#include "support/cli_run.hpp"

namespace geardyn::app {
namespace {

using test::CliRun;
using test::RunGeardyn;
using test::RunJson;

// Time integration vs harmonic balance [-], relative on the RMS DTE: HB truncation (its own
// tolerance 1e-4 linear; 24 harmonics nonlinear), the steady-state test (period-to-period change
// 1e-6 of the state) and the integrator's local error 1e-8; the RMS of 64 samples per period is
// exact (discrete Parseval) for harmonics below 32. Measured: 5e-6 (helical pair, 625 Hz) and
// 6e-5 (slice rig, 2000 Hz, 3.4 % contact loss: the DTE is only piecewise smooth there).
constexpr double kLinearHbTol = 2e-3;
constexpr double kNonlinearHbTol = 2e-3;

// The helical pair's bearings have no damping of their own: without the modal damping its
// transverse modes, excited by the start, never decay and no steady state is reached.
const std::vector<std::string> kHelical = {"builtin:helical-pair", "--set",
                                           "mesh.pinion-wheel.damping_ratio=0.05", "--set",
                                           "damping.modal_ratio=0.02"};
// The rig (LTV, contact lines): its torsional mode carries the mesh damping; fast.
const std::vector<std::string> kRigLtv = {"builtin:kahraman-blankenship-rig", "--set",
                                          "mesh.pinion-wheel.damping_ratio=0.05"};
const std::vector<std::string> kRigSlices = {"builtin:kahraman-blankenship-rig", "--set",
                                             "mesh.pinion-wheel.damping_ratio=0.05", "--set",
                                             "mesh.pinion-wheel.model=slices"};

std::vector<std::string> Cmd(const std::string& command, const std::vector<std::string>& scene,
                             std::vector<std::string> tail = {}) {
  std::vector<std::string> args = {command};
  args.insert(args.end(), scene.begin(), scene.end());
  args.insert(args.end(), tail.begin(), tail.end());
  return args;
}

std::filesystem::path OutDir(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::path(GEARDYN_BINARY_DIR) / "test_output" / "simulate_command_test" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir.parent_path());
  return dir;
}

std::vector<std::string> ReadLines(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> SplitCsv(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
  return cells;
}

TEST(SimulateCommandTest, BadOptionsExitTwoNamingTheOptionAndBound) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--tolerance", "0"},
       "--tolerance: the local relative error per step must be in [1e-14, "
       "1e-2], got 0"},
      {{"--tolerance", "0.5"}, "--tolerance"},
      {{"--steady-tolerance", "2"}, "--steady-tolerance"},
      {{"--max-periods", "0"}, "--max-periods: must be in [1, 10000000], got 0"},
      {{"--record-periods", "0"}, "--record-periods"},
      {{"--samples-per-period", "2"}, "--samples-per-period: must be in [4, 65536], got 2"},
      {{"--max-step", "0"}, "--max-step"},
      {{"--max-step", "1.5"}, "--max-step"},
      {{"--max-step", "1e-9"},
       "--max-step: the largest time step as a fraction of the mesh "
       "period must be in [1e-6, 1]"},
      {{"--threads", "-1"}, "--threads"},
      {{"--integrator", "euler"}, "--integrator: 'euler' is not one of auto"},
      {{"--sweep", "up"}, "--sweep: needs a range"},
      {{"--sweep", "sideways"}, "--sweep"},
      {{"--overlay-hb"}, "--overlay-hb"},
      {{"--quasi-static", "--mesh-frequency", "100"}, "--quasi-static"},
      {{"--mesh-frequency", "-5"}, "--mesh-frequency"},
  };
  for (const auto& [tail, message] : cases) {
    const CliRun run = RunGeardyn(Cmd("simulate", kHelical, tail));
    EXPECT_EQ(run.code, kExitBadInput) << tail.front() << ": " << run.err;
    EXPECT_NE(run.err.find(message), std::string::npos) << tail.front() << ": " << run.err;
  }
}

TEST(SimulateCommandTest, LtvDefaultRunEqualsLinearHarmonicBalance) {
  const nlohmann::json sim = RunJson(Cmd("simulate", kHelical));
  ASSERT_EQ(sim["points"].size(), 1u);
  const auto& p = sim["points"][0];
  EXPECT_EQ(sim["status"], "success");
  EXPECT_EQ(p["steady"], "steady");
  EXPECT_GT(p["periods"].get<int>(), 0);
  const double f = p["mesh_frequency_hz"].get<double>();
  const nlohmann::json hb =
      RunJson(Cmd("hb", kHelical, {"--mesh-frequency", std::to_string(f), "--stability", "none"}));
  const double rms_hb = hb["points"][0]["meshes"][0]["rms_dte_m"].get<double>();
  const double rms = p["meshes"][0]["rms_dte_m"].get<double>();
  ASSERT_GT(rms_hb, 0.0);
  EXPECT_NEAR(rms, rms_hb, kLinearHbTol * rms_hb);
  // The mean DTE is the static one: HB's mean harmonic.
  const double mean_hb = hb["points"][0]["meshes"][0]["mean_dte_m"].get<double>();
  EXPECT_NEAR(p["meshes"][0]["mean_dte_m"].get<double>(), mean_hb, kLinearHbTol * mean_hb);
  EXPECT_LT(p["max_energy_error"].get<double>(), 1e-4);  // issue 14: every run
  ASSERT_TRUE(sim.contains("run"));
  EXPECT_GT(sim["run"]["steps"].get<long>(), 0);
}

TEST(SimulateCommandTest, SliceRigDefaultRunEqualsNonlinearHarmonicBalance) {
  const nlohmann::json sim = RunJson(Cmd("simulate", kRigSlices));
  const auto& p = sim["points"][0];
  ASSERT_EQ(p["status"], "success") << p["message"];
  const double f = p["mesh_frequency_hz"].get<double>();
  EXPECT_DOUBLE_EQ(f, 2000.0);  // 2400 rpm × 50 teeth / 60
  const nlohmann::json hb = RunJson(Cmd("hb", kRigSlices, {"--mesh-frequency", "2000"}));
  EXPECT_EQ(hb["mode"], "nonlinear");
  const double rms_hb = hb["points"][0]["meshes"][0]["rms_dte_m"].get<double>();
  const double rms = p["meshes"][0]["rms_dte_m"].get<double>();
  ASSERT_GT(rms_hb, 0.0);
  EXPECT_NEAR(rms, rms_hb, kNonlinearHbTol * rms_hb);
  EXPECT_LT(p["max_energy_error"].get<double>(), 1e-4);
}

TEST(SimulateCommandTest, SweepWritesUpAndDownBranchesThatAgreeForAnLtvScene) {
  const std::filesystem::path dir = OutDir("sweep");
  const CliRun run = RunGeardyn(
      Cmd("simulate", kRigLtv,
          {"--mesh-frequency", "1000:3000:3", "--sweep", "both", "--out", dir.string()}));
  ASSERT_EQ(run.code, kExitOk) << run.err << run.out;
  const std::vector<std::string> lines = ReadLines(dir / "simulate_sweep.csv");
  ASSERT_EQ(lines.size(), 7u);  // header + 3 up + 3 down
  const std::vector<std::string> header = SplitCsv(lines[0]);
  ASSERT_GE(header.size(), 8u);
  EXPECT_EQ(header[1], "branch");
  EXPECT_EQ(header[7], "pinion-wheel:rms_dte_m");
  std::map<std::string, std::map<double, double>> rms;  // branch → f → RMS DTE
  std::vector<double> up_order, down_order;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const std::vector<std::string> c = SplitCsv(lines[i]);
    const double f = std::stod(c[2]);
    rms[c[1]][f] = std::stod(c[7]);
    (c[1] == "up" ? up_order : down_order).push_back(f);
    EXPECT_EQ(c[3], "success") << lines[i];
  }
  EXPECT_EQ(up_order, (std::vector<double>{1000, 2000, 3000}));
  EXPECT_EQ(down_order, (std::vector<double>{3000, 2000, 1000}));
  // The LTV system has one periodic steady state: both branches reach it from different starts.
  for (const auto& [f, value] : rms["up"]) {
    EXPECT_NEAR(rms["down"][f], value, kLinearHbTol * value) << f << " Hz";
  }
  const std::string svg = [&] {
    std::ifstream in(dir / "simulate_rms_dte.svg");
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }();
  EXPECT_NE(svg.find("sweep up"), std::string::npos);
  EXPECT_NE(svg.find("sweep down"), std::string::npos);
  EXPECT_NE(svg.find("RMS DTE [µm]"), std::string::npos);
}

TEST(SimulateCommandTest, FailedRunKeepsItsFiles) {
  const std::filesystem::path dir = OutDir("failed");
  const CliRun run = RunGeardyn(
      Cmd("simulate", kRigLtv,
          {"--max-periods", "1", "--steady-tolerance", "1e-14", "--out", dir.string(), "--json"}));
  EXPECT_EQ(run.code, kExitNumericalIssue) << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_EQ(report["status"], "not_converged");
  EXPECT_NE(report["points"][0]["steady"], "steady");
  EXPECT_TRUE(std::filesystem::exists(dir / "simulate.json"));
  const std::vector<std::string> dte = ReadLines(dir / "simulate_dte.csv");
  // The last integrated period's samples (64 per period) are kept.
  ASSERT_EQ(dte.size(), 65u);
  EXPECT_EQ(dte[0], "time_s,theta_rad,pinion-wheel:dte_m,pinion-wheel:force_n");
  const std::vector<std::string> energy = ReadLines(dir / "simulate_energy.csv");
  ASSERT_GE(energy.size(), 2u);  // header + every integrated period
  EXPECT_EQ(energy[0],
            "period,input_work_j,stored_change_j,dissipated_j,gross_flow_j,relative_error");
}

// A user's Ctrl-C: the real binary gets SIGINT one second into a run that cannot become steady
// (steady tolerance 1e-14, many periods); it must finish its files, say so and exit with 130.
TEST(SimulateCommandTest, InterruptWritesTheResultsSoFarAndExits130) {
  // GEARDYN_COMMAND: the sanitized twin's binary, when this runs as "sanitized:..."
  // (tests/CMakeLists).
  const char* command_override = std::getenv("GEARDYN_COMMAND");
  const std::filesystem::path binary =
      command_override != nullptr ? std::filesystem::path(command_override)
                                  : std::filesystem::path(GEARDYN_BINARY_DIR) / "apps" / "geardyn";
  ASSERT_TRUE(std::filesystem::exists(binary)) << binary;
  if (std::system("timeout --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "no timeout(1)";
  const std::filesystem::path dir = OutDir("interrupted");
  // SIGINT after 3 s (the run is endless): 1 s was too short on a loaded machine, where the
  // command had not started integrating yet (an empty error stream). --foreground: otherwise
  // timeout(1) signals the child and then its whole process group, a second SIGINT that by
  // design (a second Ctrl-C) restores the default action and kills the command before it writes
  // anything; whether it did was a race, lost whenever the parent had not ignored SIGINT.
  const std::string command = "timeout --foreground --preserve-status -s INT 3 " + binary.string() +
                              " simulate builtin:helical-pair --set "
                              "mesh.pinion-wheel.damping_ratio=0.001 --steady-tolerance 1e-14 "
                              "--max-periods 10000000 --out " +
                              dir.string() + " > " + (dir.string() + ".out") + " 2> " +
                              (dir.string() + ".err");
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status)) << command;
  EXPECT_EQ(WEXITSTATUS(status), kExitInterrupted);
  const std::vector<std::string> err = ReadLines(dir.string() + ".err");
  ASSERT_FALSE(err.empty());
  EXPECT_NE(err.back().find("interrupted (SIGINT)"), std::string::npos) << err.back();
  std::ifstream json_file(dir / "simulate.json");
  const nlohmann::json report = nlohmann::json::parse(json_file);
  EXPECT_EQ(report["interrupted"], true);
  EXPECT_NE(report["status"], "success");
  EXPECT_TRUE(std::filesystem::exists(dir / "simulate_dte.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir / "simulate_energy.csv"));
}

}  // namespace
}  // namespace geardyn::app

namespace geardyn::app {
namespace {

// Soft bearings (1e6 N/m) under the damped rig: its translational bearing modes carry no damping
// (the bearings have none) and the run started from the static equilibrium never settles. The
// message names them; truth: the closed form √(k/m)/2π = √(1e6/2.7744)/2π = 95.5511 Hz of a gear
// body (m = 2.7744 kg in the scene) on a 1e6 N/m bearing.
TEST(SimulateCommandTest, RunThatNeverSettlesNamesTheUndampedModes) {
  const std::string soft = "[1e6,1e6,1e6,1e8,1e8,0]";
  const CliRun run =
      RunGeardyn(Cmd("simulate", kRigLtv,
                     {"--set", "bearing.pinion-support.stiffness=" + soft, "--set",
                      "bearing.wheel-support.stiffness=" + soft, "--max-periods", "30", "--json"}));
  EXPECT_EQ(run.code, kExitNumericalIssue) << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  const std::string message = report["message"].get<std::string>();
  EXPECT_NE(message.find("undamped modes"), std::string::npos) << message;
  const double f = std::sqrt(1e6 / 2.7744) / (2.0 * M_PI);
  char expected[32];
  std::snprintf(expected, sizeof(expected), "%.6g Hz", f);
  EXPECT_NE(message.find(expected), std::string::npos) << expected << " in " << message;
  EXPECT_NE(report["points"][0]["steady"], "steady");
}

}  // namespace
}  // namespace geardyn::app
