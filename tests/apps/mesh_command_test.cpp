// `geardyn mesh`: the sampled mesh parameters against the geometry's closed forms (contact-line
// lengths, contact ratio), the ISO mean stiffness, and the files it writes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "geardyn/cli.hpp"
#include "support/cli_run.hpp"

namespace geardyn::app {
namespace {

using test::CliRun;
using test::RunGeardyn;
using test::RunJson;

// Reads a CSV written by the command: header + rows of numbers.
std::vector<std::vector<double>> ReadCsv(const std::filesystem::path& path, std::string* header) {
  std::ifstream in(path);
  std::getline(in, *header);
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<double> row;
    std::stringstream ls(line);
    for (std::string cell; std::getline(ls, cell, ',');) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

TEST(MeshCommandTest, SpurRigAlternatesBetweenOneAndTwoPairLevels) {
  const nlohmann::json info = RunJson({"info", "builtin:kahraman-blankenship-rig"})["meshes"][0];
  const nlohmann::json mesh = RunJson({"mesh", "builtin:kahraman-blankenship-rig"})["meshes"][0];
  const double eps_alpha = info["transverse_contact_ratio"].get<double>();
  // Constant k along the lines: K ∝ total contact length, one full-face line (b) or two (2b).
  EXPECT_NEAR(
      mesh["stiffness"]["max"].get<double>() / mesh["stiffness"]["min"].get<double>(),
      info["max_contact_line_length"].get<double>() / info["min_contact_line_length"].get<double>(),
      1e-12);
  // The mean over the period: K̄ = c_γα · B exactly (ISO 6336-1 mesh stiffness per unit face
  // width; k = c_γα B / L̄). It is the coefficient's exact mean, not the 360-sample rectangle rule
  // (which read 0.1 % low).
  const double sample_tol = 2.0 / 360.0;  // one sample per jump of the rectangular wave
  EXPECT_NEAR(mesh["stiffness"]["mean"].get<double>() /
                  (info["mesh_stiffness_alpha"].get<double>() * info["face_width"].get<double>()),
              1.0, 1e-12);
  // Spur: the load centre stays on the face centre (h = 0) and μ = 1/3 (full-face lines).
  EXPECT_NEAR(mesh["load_centre"]["max"].get<double>(), 0.0, 1e-15);
  EXPECT_NEAR(mesh["mu"]["min"].get<double>(), 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(mesh["mu"]["max"].get<double>(), 1.0 / 3.0, 1e-12);
  EXPECT_EQ(mesh["time_dependence"].get<std::string>(), "piecewise_constant");
  EXPECT_EQ(mesh["period_meshes"].get<long>(), 1);

  // Fraction of the period with two pairs in contact = ε_α − 1.
  const std::filesystem::path dir =
      std::filesystem::path(GEARDYN_BINARY_DIR) / "test-output" / "mesh_spur";
  std::filesystem::remove_all(dir);
  ASSERT_EQ(RunGeardyn({"mesh", "builtin:kahraman-blankenship-rig", "--out", dir.string()}).code,
            kExitOk);
  std::string header;
  const auto rows = ReadCsv(dir / "mesh_pinion-wheel.csv", &header);
  ASSERT_EQ(rows.size(), 360u);
  EXPECT_EQ(header.rfind("cycle,stiffness_N_per_m", 0), 0u);
  const double k_max = mesh["stiffness"]["max"].get<double>();
  const long two_pair =
      std::count_if(rows.begin(), rows.end(), [&](const auto& r) { return r[1] > 0.75 * k_max; });
  EXPECT_NEAR(static_cast<double>(two_pair) / 360.0, eps_alpha - 1.0, sample_tol);
  EXPECT_TRUE(std::filesystem::exists(dir / "mesh_pinion-wheel.svg"));
  EXPECT_TRUE(std::filesystem::exists(dir / "mesh.json"));
}

TEST(MeshCommandTest, HelicalStiffnessRangeFollowsContactLineClosedForms) {
  const nlohmann::json info = RunJson({"info", "builtin:helical-pair"})["meshes"][0];
  const nlohmann::json mesh =
      RunJson({"mesh", "builtin:helical-pair", "--samples", "2000"})["meshes"][0];
  // K = k L(θ) with constant k: the sampled range within a sampling step of the closed forms.
  const double mean_k = mesh["stiffness"]["mean"].get<double>();
  const double l_mean = info["mean_contact_line_length"].get<double>();
  constexpr double kSampledTol = 5e-3;  // Fourier form (rel. L2 1e-4) sampled at 2000 points
  EXPECT_NEAR(mesh["stiffness"]["max"].get<double>() / mean_k,
              info["max_contact_line_length"].get<double>() / l_mean, kSampledTol);
  EXPECT_NEAR(mesh["stiffness"]["min"].get<double>() / mean_k,
              info["min_contact_line_length"].get<double>() / l_mean, kSampledTol);
}

TEST(MeshCommandTest, RunoutExtendsThePeriodToTheHuntingPeriod) {
  // Runout of one gear repeats once per revolution of that gear; with z 50/50 the sampled period
  // becomes the hunting period lcm(50, 50) = 50 mesh cycles, and ε_η varies sinusoidally with an
  // amplitude of cos β_b · e (spur: the full eccentricity projected on the line of action).
  constexpr double kRunout = 10e-6;  // m
  const std::filesystem::path dir =
      std::filesystem::path(GEARDYN_BINARY_DIR) / "test-output" / "mesh_runout";
  std::filesystem::remove_all(dir);
  const CliRun run =
      RunGeardyn({"mesh", "builtin:kahraman-blankenship-rig", "--samples", "32", "--set",
                  "mesh.pinion-wheel.errors.gear_runout=1e-5", "--out", dir.string(), "--json"});
  ASSERT_EQ(run.code, kExitOk) << run.err;
  const nlohmann::json mesh = nlohmann::json::parse(run.out)["meshes"][0];
  EXPECT_EQ(mesh["period_meshes"].get<long>(), 50);
  std::string header;
  const auto rows = ReadCsv(dir / "mesh_pinion-wheel.csv", &header);
  ASSERT_EQ(rows.size(), 50u * 32u);
  EXPECT_NE(header.find("te_eta_m"), std::string::npos);
  // A uniform separation on every contact line gives ε_η equal to it (spec 01 §3), so the
  // sampled ε_η spans ±e: peak-to-peak 2e within the sampling of one revolution (32·50 points).
  const double sampling = 1.0 - std::cos(M_PI / (32.0 * 50.0));
  EXPECT_NEAR(mesh["te_eta"]["peak_to_peak"].get<double>(), 2.0 * kRunout,
              2.0 * kRunout * sampling + 1e-12);
  EXPECT_NEAR(mesh["te_eta"]["mean"].get<double>(), 0.0, 1e-3 * kRunout);
}

TEST(MeshCommandTest, BadSampleCountIsRejected) {
  const CliRun run = RunGeardyn({"mesh", "builtin:helical-pair", "--samples", "-3"});
  EXPECT_EQ(run.code, kExitBadInput);
  EXPECT_NE(run.err.find("--samples"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace geardyn::app
