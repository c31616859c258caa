// `geardyn matrices`: the exported MatrixMarket files, read back with Eigen's own reader
// (unsupported/Eigen/SparseExtra loadMarket, independent of our writer), give by an independent
// dense generalized eigen solve (Eigen's GeneralizedSelfAdjointEigenSolver) the frequencies of
// `geardyn modes`; the DOF map names every row; K_0 of the harmonics is the mean K for linear
// cores; K(θ) rebuilt from the harmonics equals the assembled K(θ); bad options name the flag.
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
    const double top = expected.back();
    for (Eigen::Index i = 0; i < k.rows(); ++i) {
      const double lambda = std::max(0.0, solver.eigenvalues()(i));
      const double f = std::sqrt(lambda) / (2.0 * std::numbers::pi);
      EXPECT_NEAR(f, expected[i], kSolverAgreement * top) << scene << " mode " << i;
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
    const bool rotation = map.dof_kind(i) == DofKind::kRotationAxial ||
                          map.dof_kind(i) == DofKind::kRotationTilt;
    EXPECT_EQ(d["unit"].get<std::string>(), rotation ? "rad" : "m") << d.dump();
  }
}

// K(θ) = K_0 + 2 Re Σ_{m≥1} K_m e^{imθ/P} against the workspace's K(θ) at a few phases: the
// smooth ISO-stiffness helical pair has a Fourier series that converges fast; 64 harmonics
// leave a truncation error far below 1e-6 of K there.
TEST(MatricesCommand, HarmonicsRebuildTheAssembledStiffness) {
  const Scene scene = LoadScene("builtin:helical-pair");
  const SystemMatrices x = ExportSystemMatrices(scene, 64);
  const SceneSystem built = BuildSceneSystem(scene);
  SystemWorkspace ws(built.model, StorageKind::kDense);
  const double p = static_cast<double>(x.harmonics.period_meshes);
  EXPECT_LT((MatrixX(x.mean.stiffness) - x.harmonics.stiffness[0].real()).norm(),
            1e-12 * MatrixX(x.mean.stiffness).norm());
  double worst = 0.0;
  for (double theta : {0.0, 0.7, 2.9, 5.1}) {
    MatrixXc sum = x.harmonics.stiffness[0];
    for (int m = 1; m <= x.harmonics.num_harmonics(); ++m) {
      const std::complex<double> e = std::exp(std::complex<double>(0.0, m * theta / p));
      sum += x.harmonics.stiffness[m] * e + x.harmonics.stiffness[m].conjugate() * std::conj(e);
    }
    const MatrixX& assembled = AssembleStiffness(built.model, ws, theta);
    worst = std::max(worst, (sum.real() - assembled).norm() / assembled.norm());
  }
  EXPECT_LT(worst, 1e-6);
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
