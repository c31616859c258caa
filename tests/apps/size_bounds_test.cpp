// Every size and count a command accepts is bounded, each bound tested at its edge (just inside
// accepted, just outside rejected with a message naming the option, the value, the bound and the
// cost), and a bad --out is refused before anything is computed (issue 12, "sizes").
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "geardyn/analyses/stability_chart.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/mesh_report.hpp"
#include "geardyn/models/gear/gear_geometry.hpp"
#include "support/cli_run.hpp"

namespace geardyn {
namespace {

using test::CliRun;
using test::RunGeardyn;
using test::RunJson;

constexpr const char* kPair = "builtin:helical-pair";
constexpr const char* kRig = "builtin:kahraman-blankenship-rig";

void ExpectRejected(const std::vector<std::string>& args, const std::vector<std::string>& parts) {
  const CliRun run = RunGeardyn(args);
  EXPECT_EQ(run.code, app::kExitBadInput) << run.out;
  for (const std::string& p : parts) EXPECT_NE(run.err.find(p), std::string::npos) << run.err;
}

// ------------------------------------------------------------------ mesh --samples

TEST(SizeBoundsTest, MeshSamplesZeroIsRejectedAndOneIsAccepted) {
  // "0" used to mean "automatic" although the message said "positive": now omitting the option
  // is the only way to ask for the automatic count.
  ExpectRejected({"mesh", kPair, "--samples", "0"}, {"--samples", "must be ≥ 1", "got 0"});
  const nlohmann::json one = RunJson({"mesh", kPair, "--samples", "1"})["meshes"][0];
  EXPECT_EQ(one["samples_per_mesh"].get<int>(), 1);
  const nlohmann::json automatic = RunJson({"mesh", kPair})["meshes"][0];
  EXPECT_EQ(automatic["samples_per_mesh"].get<int>(), 360);
}

TEST(SizeBoundsTest, MeshSamplesPerCycleBoundAtItsEdge) {
  const long max = app::MeshSamplingOptions::kMaxSamplesPerMesh;
  const nlohmann::json inside =
      RunJson({"mesh", kPair, "--samples", std::to_string(max)})["meshes"][0];
  EXPECT_EQ(inside["samples_per_mesh"].get<long>(), max);
  ExpectRejected({"mesh", kPair, "--samples", std::to_string(max + 1)},
                 {"--samples", "must be ≤ 100000", "GB in memory"});
  ExpectRejected({"mesh", kPair, "--samples", "2e9"}, {"--samples", "must be ≤ 100000"});
}

TEST(SizeBoundsTest, MeshRowsOverAHuntingPeriodBoundAtItsEdge) {
  // The rig's 50/50 pair with a runout repeats after 50 mesh cycles: 40000 samples per cycle
  // give exactly the 2·10⁶-row limit, 40001 exceed it.
  const long max_rows = app::MeshSamplingOptions::kMaxSamples;
  ASSERT_EQ(max_rows % 50, 0);
  const std::string runout = "mesh.pinion-wheel.errors.gear_runout=1e-5";
  ExpectRejected({"mesh", kRig, "--set", runout, "--samples", std::to_string(max_rows / 50 + 1)},
                 {"--samples", "50 mesh cycles", "exceed the limit 2000000", "GB of CSV"});
  const nlohmann::json inside = RunJson(
      {"mesh", kRig, "--set", runout, "--samples", std::to_string(max_rows / 50)})["meshes"][0];
  EXPECT_EQ(inside["period_meshes"].get<long>() * inside["samples_per_mesh"].get<long>(), max_rows);
}

// ------------------------------------------------------------------ coprime teeth, ε table

// 997/991 teeth with a runout: ε repeats over P = 988 027 mesh cycles.
std::vector<std::string> CoprimeRunout(std::vector<std::string> args) {
  for (const char* set : {"gear.pinion.teeth=997", "gear.wheel.teeth=991",
                          "mesh.pinion-wheel.errors.gear_runout=1e-5"}) {
    args.insert(args.end(), {"--set", set});
  }
  return args;
}

TEST(SizeBoundsTest, MeshSamplesAWindowOfTheHuntingPeriod) {
  // Default: the first kMaxAutoCycles cycles at 16 samples, with a warning naming the period.
  const nlohmann::json automatic = RunJson(CoprimeRunout({"mesh", kPair}))["meshes"][0];
  EXPECT_EQ(automatic["period_meshes"].get<long>(), 988027);
  EXPECT_EQ(automatic["cycles"].get<long>(), app::MeshSamplingOptions::kMaxAutoCycles);
  EXPECT_EQ(automatic["samples_per_mesh"].get<long>(), 16);
  bool warned = false;
  for (const nlohmann::json& w : automatic["warnings"]) {
    warned |=
        w.get<std::string>().find("first 12500 of the 988027 mesh cycles") != std::string::npos;
  }
  EXPECT_TRUE(warned) << automatic["warnings"].dump();
  // --cycles: what the user asks for, at the automatic 360 samples per cycle.
  const nlohmann::json three =
      RunJson(CoprimeRunout({"mesh", kPair, "--cycles", "3"}))["meshes"][0];
  EXPECT_EQ(three["cycles"].get<long>(), 3);
  EXPECT_EQ(three["samples_per_mesh"].get<long>(), 360);
  ExpectRejected({"mesh", kPair, "--cycles", "0"}, {"--cycles", "must be an integer", "got 0"});
  ExpectRejected({"mesh", kPair, "--cycles", "1.5"}, {"--cycles", "got 1.5"});
  ExpectRejected({"mesh", kPair, "--cycles", "20001", "--samples", "100"},
                 {"--samples", "20001 mesh cycles (--cycles)", "exceed the limit 2000000"});
}

TEST(SizeBoundsTest, TransmissionErrorTableOverAHuntingPeriodIsBounded) {
  // A forced response that needs ε as a table over the hunting period (the slice model, or pitch
  // errors): 256 samples × 988 027 cycles = 2.5·10⁸ (4 GB) are refused at once, naming the period
  // and the cost; so are 17 samples per cycle (1.68·10⁷ > 2^24 = 1.678·10⁷; 16 would pass).
  const std::vector<std::string> slices = {"--set", "mesh.pinion-wheel.model=slices"};
  std::vector<std::string> args =
      CoprimeRunout({"hb", kPair, "--mesh-frequency", "2500", "--harmonics", "1"});
  args.insert(args.end(), slices.begin(), slices.end());
  ExpectRejected(args, {"mesh.pinion-wheel.errors", "hunting period of 988027 mesh cycles",
                        "lcm of 997 and 991", "GB", "above the limit 16777216"});
  args.insert(args.end(), {"--set", "mesh.pinion-wheel.table_samples=17"});
  ExpectRejected(args, {"17 samples per cycle would hold 16796459 samples"});
  // The homogeneous analyses build no ε: the same scene runs.
  EXPECT_GT(RunJson(CoprimeRunout({"modes", kPair}))["modes"].size(), 0u);
}

TEST(SizeBoundsTest, LinearHbSolvesCoprimeTeethWithARunoutBySparseHarmonics) {
  // The runout alone on a linear level: two lines over the hunting period (sidebands), solved
  // class by class. Class 0 (the mesh orders) is the response without the runout (mean DTE
  // equal), and the RMS adds the runout classes (Parseval).
  const std::vector<std::string> base = {
      "hb", kPair,   "--mesh-frequency",      "2500",  "--harmonics",
      "8",  "--set", "gear.pinion.teeth=997", "--set", "gear.wheel.teeth=991"};
  const nlohmann::json with = RunJson(
      CoprimeRunout({"hb", kPair, "--mesh-frequency", "2500", "--harmonics", "8"}))["points"][0];
  const nlohmann::json without = RunJson(base)["points"][0];
  EXPECT_EQ(with["status"], "success");
  EXPECT_TRUE(with["sparse_harmonics"].get<bool>());
  EXPECT_EQ(with["period_meshes"].get<long>(), 988027);
  EXPECT_EQ(with["kept_harmonics"].size(), 9u + 17u);  // j q (j ≤ 8) and j q ± 997
  const nlohmann::json& a = with["meshes"][0];
  const nlohmann::json& b = without["meshes"][0];
  EXPECT_NEAR(a["mean_dte_m"].get<double>(), b["mean_dte_m"].get<double>(),
              1e-9 * std::abs(b["mean_dte_m"].get<double>()));
  EXPECT_GE(a["rms_dte_m"].get<double>(), b["rms_dte_m"].get<double>() * (1.0 - 1e-12));
  const CliRun text = RunGeardyn(CoprimeRunout({"hb", kPair, "--mesh-frequency", "2500"}));
  EXPECT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("sparse harmonics"), std::string::npos) << text.out;
}

// ------------------------------------------------------------------ stability-chart

TEST(SizeBoundsTest, ChartGridBoundAtItsEdge) {
  const auto axis = [](int n) { return ChartAxis{"p", 0.0, 1.0, n}; };
  std::string why;
  EXPECT_TRUE(IsValidChartGrid(axis(1000), axis(1000), &why));
  EXPECT_TRUE(IsValidChartGrid(axis(kMaxChartAxisPoints), axis(100), &why));
  EXPECT_FALSE(IsValidChartGrid(axis(1001), axis(1000), &why));
  EXPECT_NE(why.find("1001000 points exceed the limit 1000000"), std::string::npos) << why;
  EXPECT_TRUE(axis(kMaxChartAxisPoints).IsValid("x", &why));
  EXPECT_FALSE(axis(kMaxChartAxisPoints + 1).IsValid("x", &why));
  EXPECT_NE(why.find("at most 10000"), std::string::npos) << why;
  // The CLI refuses a 1e5 × 1e5 chart before building a model.
  ExpectRejected({"stability-chart", kPair, "--x", "operating_point.speed_rpm=1000:2000:100000",
                  "--y", "operating_point.torque=100:200:2"},
                 {"--x", "at most 10000"});
  ExpectRejected({"stability-chart", kPair, "--x", "operating_point.speed_rpm=1000:2000:10000",
                  "--y", "operating_point.torque=100:200:101"},
                 {"1010000 points exceed the limit 1000000", "Floquet solves", "GB"});
}

TEST(SizeBoundsTest, ChartThreadsAreClampedToTheWorkWithAWarning) {
  // 70000 threads used to segfault inside OpenMP; a 2 × 2 grid needs at most 4.
  const nlohmann::json j =
      RunJson({"stability-chart", kPair, "--x", "operating_point.speed_rpm=3000:9000:2", "--y",
               "operating_point.torque=100:200:2", "--threads", "70000", "--tolerance", "1e-6",
               "--no-curves"});
  EXPECT_LE(j["counters"]["threads"].get<long>(), 4);
  bool warned = false;
  for (const nlohmann::json& w : j["warnings"]) {
    warned = warned || w.get<std::string>().find("num_threads: 70000 requested") == 0;
  }
  EXPECT_TRUE(warned) << j["warnings"].dump();
}

// ------------------------------------------------------------------ module and contact lines

TEST(SizeBoundsTest, TinyModuleIsRejectedBeforeAnyWork) {
  // A module of 1e-10 m used to hang `modes` (ε_β in the millions of contact lines).
  ExpectRejected({"modes", kPair, "--set", "gear.pinion.normal_module=1e-10", "--set",
                  "gear.wheel.normal_module=1e-10"},
                 {"normal_module", "at least 1e-05 m", "1e-10"});
}

GearPairSpec HelicalSpec(double module, double face_width) {
  GearPairSpec s;
  s.normal_module = module;
  s.normal_pressure_angle = 20.0 * M_PI / 180.0;
  s.helix_angle = 15.0 * M_PI / 180.0;
  s.pinion_hand = HelixHand::kRight;
  s.pinion.teeth = 25;
  s.gear.teeth = 61;
  s.pinion.face_width = s.gear.face_width = face_width;
  return s;
}

TEST(SizeBoundsTest, ModuleBoundAtItsEdge) {
  // Geometry scales with the module: 20 modules of face width keep ε_β ≈ 1.6 at any scale.
  const GearPairGeometry g =
      CalcGearPairGeometry(HelicalSpec(kMinNormalModule, 20 * kMinNormalModule));
  EXPECT_NEAR(g.overlap_contact_ratio, 20.0 * std::sin(15.0 * M_PI / 180.0) / M_PI, 1e-12);
  const double below = kMinNormalModule * (1.0 - 1e-9);
  try {
    CalcGearPairGeometry(HelicalSpec(below, 20 * below));
    ADD_FAILURE() << "a module below the bound was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("normal_module: must be at least 1e-05 m"),
              std::string::npos)
        << e.what();
  }
}

TEST(SizeBoundsTest, OverlapRatioBoundAtItsEdge) {
  // ε_β = b sin β / (π m_n) = kMaxOverlapRatio at b = kMaxOverlapRatio·π·m_n / sin β.
  const double m = 3e-3, b_edge = kMaxOverlapRatio * M_PI * m / std::sin(15.0 * M_PI / 180.0);
  const GearPairGeometry g = CalcGearPairGeometry(HelicalSpec(m, b_edge * (1.0 - 1e-9)));
  EXPECT_LE(g.overlap_contact_ratio, kMaxOverlapRatio);
  try {
    CalcGearPairGeometry(HelicalSpec(m, b_edge * (1.0 + 1e-9)));
    ADD_FAILURE() << "an overlap ratio above the bound was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("overlap_contact_ratio: "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("exceeds 100"), std::string::npos) << e.what();
  }
}

// ------------------------------------------------------------------ --out

TEST(SizeBoundsTest, FileInTheWayOfOutIsRefusedBeforeComputingForEveryCommand) {
  const std::filesystem::path file =
      std::filesystem::path(GEARDYN_BINARY_DIR) / "test_output" / "size_bounds_file_in_the_way";
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file) << "not a directory\n";
  const std::vector<std::vector<std::string>> commands = {
      {"info", kPair},
      {"mesh", kPair},
      {"modes", kPair},
      {"floquet", kPair},
      {"hb", kPair},
      {"stability-chart", kPair, "--x", "operating_point.speed_rpm=1000:2000:3", "--y",
       "operating_point.torque=100:200:3"}};
  for (std::vector<std::string> args : commands) {
    args.push_back("--out");
    args.push_back(file.string());
    const CliRun run = RunGeardyn(args);
    EXPECT_EQ(run.code, app::kExitBadInput) << args[0];
    EXPECT_NE(run.err.find("--out"), std::string::npos) << args[0] << ": " << run.err;
    EXPECT_NE(run.err.find("not a directory"), std::string::npos) << args[0] << ": " << run.err;
    EXPECT_EQ(run.out, "") << args[0] << " computed before refusing --out";
  }
}

TEST(SizeBoundsTest, UnwritableOutDirectoryIsRefusedBeforeComputing) {
  if (geteuid() == 0) GTEST_SKIP() << "root writes anywhere: no unwritable directory to test";
  const std::filesystem::path dir =
      std::filesystem::path(GEARDYN_BINARY_DIR) / "test_output" / "size_bounds_read_only";
  std::filesystem::create_directories(dir);
  std::filesystem::permissions(
      dir, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  const CliRun run = RunGeardyn({"modes", kPair, "--out", dir.string()});
  std::filesystem::permissions(dir, std::filesystem::perms::owner_all);
  EXPECT_EQ(run.code, app::kExitBadInput);
  EXPECT_NE(run.err.find("not writable"), std::string::npos) << run.err;
  EXPECT_EQ(run.out, "");
}

}  // namespace
}  // namespace geardyn
