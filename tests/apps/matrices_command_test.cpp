// `geardyn matrices`: the exported MatrixMarket files, read back with Eigen's own reader
// (unsupported/Eigen/SparseExtra loadMarket, independent of our writer), give by an independent
// dense generalized eigen solve (Eigen's GeneralizedSelfAdjointEigenSolver) the frequencies of
// `geardyn modes`; the DOF map names every row; K_0 of the harmonics is the mean K for linear
// cores; the harmonics equal a quadrature of the assembled K(θ); bad options name the flag.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <unsupported/Eigen/SparseExtra>
#include <vector>

#include "geardyn/matrices_export.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/system/workspace.hpp"
#include "support/cli_run.hpp"

namespace geardyn::app {
namespace {

using test::RunGeardyn;
using test::RunJson;

// Two dense eigen solvers on the same pencil (ours: Cholesky-reduced LAPACK/Eigen path of
// ComputeModes; here Eigen's GeneralizedSelfAdjointEigenSolver), relative to the top frequency.
constexpr double kSolverAgreement = 1e-9;

std::filesystem::path TempDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("geardyn_matrices_" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

SparseMatrix Load(const std::filesystem::path& file) {
  SparseMatrix a;
  EXPECT_TRUE(Eigen::loadMarket(a, file.string())) << file;
  return a;
}

TEST(MatricesCommand, ExportedPencilGivesTheFrequenciesOfModes) {
  for (const std::string scene :
       {"builtin:helical-pair", "builtin:kahraman-blankenship-rig", "builtin:geared-shafts"}) {
    const auto dir = TempDir("pencil");
    const auto run = RunGeardyn({"matrices", scene, "--out", dir.string()});
    ASSERT_EQ(run.code, 0) << run.err;
    const MatrixX k = MatrixX(Load(dir / "K.mtx"));
    const MatrixX m = MatrixX(Load(dir / "M.mtx"));
    ASSERT_EQ(k.rows(), m.rows());
    const nlohmann::json modes =
        RunJson({"modes", scene, "--modes", std::to_string(k.rows()), "--method", "dense"});
    const auto expected = modes["frequencies_hz"].get<std::vector<double>>();
    ASSERT_EQ(static_cast<Eigen::Index>(expected.size()), k.rows()) << scene;
    Eigen::GeneralizedSelfAdjointEigenSolver<MatrixX> solver(k, m, Eigen::EigenvaluesOnly);
    ASSERT_EQ(solver.info(), Eigen::Success);
    // Compared as eigenvalues λ = (2πf)²: a rigid-body mode's λ is round-off of λ_max (4e-17
    // relative here), which the square root would blow up to 1e-4 Hz.
    const double top = std::pow(2.0 * std::numbers::pi * expected.back(), 2);
    for (Eigen::Index i = 0; i < k.rows(); ++i) {
      const double lambda = std::pow(2.0 * std::numbers::pi * expected[i], 2);
      EXPECT_NEAR(solver.eigenvalues()(i), lambda, kSolverAgreement * top)
          << scene << " mode " << i;
    }
    // Symmetric pencil, written in full.
    EXPECT_LT((k - k.transpose()).norm(), 1e-12 * k.norm()) << scene;
    EXPECT_EQ((m - m.transpose()).norm(), 0.0) << scene;
  }
}

TEST(MatricesCommand, DofMapNamesEveryRowAndItsUnit) {
  const auto dir = TempDir("dofs");
  ASSERT_EQ(RunGeardyn({"matrices", "builtin:helical-pair", "--out", dir.string()}).code, 0);
  std::ifstream in(dir / "dofs.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  const SceneSystem built = BuildSceneSystem(LoadScene("builtin:helical-pair"));
  const DofMap& map = built.model.dof_map();
  ASSERT_EQ(j["num_dofs"].get<int>(), map.num_dofs());
  ASSERT_EQ(j["dofs"].size(), static_cast<std::size_t>(map.num_dofs()));
  for (int i = 0; i < map.num_dofs(); ++i) {
    const nlohmann::json& d = j["dofs"][i];
    EXPECT_EQ(d["name"].get<std::string>(), map.dof_name(i));
    EXPECT_EQ(d["body"].get<std::string>(), map.body_name(map.dof_body(i)));
    const bool rotation =
        map.dof_kind(i) == DofKind::kRotationAxial || map.dof_kind(i) == DofKind::kRotationTilt;
    EXPECT_EQ(d["unit"].get<std::string>(), rotation ? "rad" : "m") << d.dump();
  }
}

// K_m against an independent quadrature: the rectangle rule on N samples of the assembled K(θ)
// (workspace kernels), K_m = mean_j K(θ_j) e^{−imθ_j/P}. The helical pair's K(θ) has steps of
// 1.4 % of its mean (contact lines entering and leaving), so the rule's error is about
// step / N ≈ 3e-6 of K at N = 4096; the library's K_m are the exact closed form (sinc sums).
TEST(MatricesCommand, HarmonicsEqualAQuadratureOfTheAssembledStiffness) {
  const Scene scene = LoadScene("builtin:helical-pair");
  const SystemMatrices x = ExportSystemMatrices(scene, 4);
  const SceneSystem built = BuildSceneSystem(scene);
  SystemWorkspace ws(built.model, StorageKind::kDense);
  const double p = static_cast<double>(x.harmonics.period_meshes);
  ASSERT_EQ(p, 1.0);  // no tooth errors: one mesh cycle
  const double scale = MatrixX(x.mean.stiffness).norm();
  EXPECT_LT((MatrixX(x.mean.stiffness) - x.harmonics.stiffness[0].real()).norm(), 1e-12 * scale);
  constexpr int kSamples = 4096;
  std::vector<MatrixXc> quadrature(
      5, MatrixXc::Zero(x.mean.stiffness.rows(), x.mean.stiffness.cols()));
  for (int j = 0; j < kSamples; ++j) {
    const double theta = 2.0 * std::numbers::pi * p * j / kSamples;
    const MatrixX& k = AssembleStiffness(built.model, ws, theta);
    for (int m = 0; m <= 4; ++m) {
      quadrature[m] += k.cast<std::complex<double>>() *
                       std::exp(std::complex<double>(0.0, -m * theta / p)) / double{kSamples};
    }
  }
  for (int m = 0; m <= 4; ++m) {
    EXPECT_LT((quadrature[m] - x.harmonics.stiffness[m]).norm(), 1e-5 * scale) << "m = " << m;
  }
  // And the first harmonic is not trivially zero.
  EXPECT_GT(x.harmonics.stiffness[1].norm(), 1e-3 * scale);
}

TEST(MatricesCommand, MatrixMarketTextRoundTripsThroughEigensReader) {
  const Scene scene = LoadScene("builtin:kahraman-blankenship-rig");
  const SystemMatrices x = ExportSystemMatrices(scene, 0);
  const auto dir = TempDir("roundtrip");
  WriteSystemMatrices(x, dir.string());
  const SparseMatrix k = Load(dir / "K.mtx");
  EXPECT_EQ((MatrixX(k) - MatrixX(x.mean.stiffness)).cwiseAbs().maxCoeff(), 0.0);  // %.17g
  // f.mtx is coordinate n×1; Eigen's reader takes it as a sparse matrix.
  const SparseMatrix fs = Load(dir / "f.mtx");
  ASSERT_EQ(fs.rows(), x.mean_load.size());
  EXPECT_EQ((MatrixX(fs).col(0) - x.mean_load).cwiseAbs().maxCoeff(), 0.0);
}

TEST(MatricesCommand, BadOptionsNameTheFlag) {
  const auto no_out = RunGeardyn({"matrices", "builtin:helical-pair"});
  EXPECT_EQ(no_out.code, 2);
  EXPECT_NE(no_out.err.find("--out"), std::string::npos) << no_out.err;
  const auto dir = TempDir("bad");
  const auto too_many =
      RunGeardyn({"matrices", "builtin:helical-pair", "--out", dir.string(), "--harmonics", "-1"});
  EXPECT_EQ(too_many.code, 2);
  EXPECT_NE(too_many.err.find("--harmonics"), std::string::npos) << too_many.err;
  EXPECT_THROW(ExportSystemMatrices(LoadScene("builtin:helical-pair"), kMaxExportHarmonics + 1),
               InvalidInput);
}

}  // namespace
}  // namespace geardyn::app
