// Each input is asked for only where an analysis needs it: a scene without mass properties goes
// through `info` and `mesh` with the same geometry and stiffness as with them (neither uses a
// mass), and an analysis that builds the mass matrix names itself in the error, at the gear's
// table in the file.
//
// Independent truth: the same commands on the built-in scene the stripped file was made from
// (the masses are the only difference, so every geometry and stiffness number must be equal).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>

#include "geardyn/models/scene/builtin_scenes.hpp"
#include "support/cli_run.hpp"

namespace geardyn {
namespace {

using nlohmann::json;
using test::RunGeardyn;
using test::RunJson;

// The built-in helical pair without any mass, inertia or transverse_inertia line; `removed`
// counts the lines taken out.
std::string HelicalPairWithoutMasses(int* removed) {
  std::istringstream in(std::string(*BuiltinSceneText("helical-pair")));
  const std::regex mass_key(R"(^\s*(mass|inertia|transverse_inertia)\s*=)");
  std::string text, line;
  *removed = 0;
  while (std::getline(in, line)) {
    if (std::regex_search(line, mass_key)) {
      ++*removed;
      continue;
    }
    text += line + "\n";
  }
  return text;
}

std::string WriteScene(const std::string& name, const std::string& text) {
  const std::filesystem::path dir = std::filesystem::path(GEARDYN_BINARY_DIR) / "test-output";
  std::filesystem::create_directories(dir);
  const std::filesystem::path path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

// 1-based line of the first line equal to `wanted` in `text`.
int LineOf(const std::string& text, const std::string& wanted) {
  std::istringstream in(text);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line == wanted) return n;
  }
  return 0;
}

class SceneWithoutMassesTest : public testing::Test {
 protected:
  void SetUp() override {
    int removed = 0;
    text_ = HelicalPairWithoutMasses(&removed);
    ASSERT_EQ(removed, 6);  // mass, inertia, transverse_inertia of the pinion and the wheel
    path_ = WriteScene("helical_pair_without_masses.toml", text_);
  }
  std::string text_;
  std::string path_;
};

TEST_F(SceneWithoutMassesTest, InfoGivesTheSameGeometryAndStiffness) {
  const json with = RunJson({"info", "builtin:helical-pair"});
  const json without = RunJson({"info", path_});
  ASSERT_EQ(without["meshes"].size(), 1u);
  // Every mesh number (geometry, ISO 6336-1 stiffness, frequencies) is identical.
  EXPECT_EQ(without["meshes"], with["meshes"]);
  ASSERT_EQ(without["gears"].size(), with["gears"].size());
  for (std::size_t i = 0; i < with["gears"].size(); ++i) {
    json a = with["gears"][i];
    json b = without["gears"][i];
    EXPECT_TRUE(b["mass"].is_null());
    EXPECT_TRUE(b["inertia"].is_null());
    a.erase("mass");
    a.erase("inertia");
    b.erase("mass");
    b.erase("inertia");
    EXPECT_EQ(b, a);
  }
}

TEST_F(SceneWithoutMassesTest, MeshGivesTheSameStiffness) {
  const json with = RunJson({"mesh", "builtin:helical-pair"});
  const json without = RunJson({"mesh", path_});
  EXPECT_EQ(without["meshes"], with["meshes"]);
}

TEST_F(SceneWithoutMassesTest, AnalysesThatNeedTheMassMatrixNameThemselves) {
  const int pinion_line = LineOf(text_, "[[gear]]");
  ASSERT_GT(pinion_line, 0);
  for (const std::string analysis : {"modes", "floquet"}) {
    const test::CliRun run = RunGeardyn({analysis, path_});
    EXPECT_NE(run.code, app::kExitOk) << analysis;
    EXPECT_NE(run.err.find("helical_pair_without_masses.toml:" + std::to_string(pinion_line) +
                           ": gear.pinion.mass: required by " + analysis + " (mass matrix)"),
              std::string::npos)
        << run.err;
  }
}

}  // namespace
}  // namespace geardyn
