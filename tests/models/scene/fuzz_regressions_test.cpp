// Replays the fuzz inputs (tests/fuzz/corpus/<target>/ and tests/fuzz/regressions/<target>/)
// through the same entry functions the libFuzzer targets run (tests/fuzz/fuzz_entries.hpp), in
// the normal build: each must return normally (a Scene and a built model with finite numbers,
// or InvalidInput naming the source). Issue 16; docs/fuzzing.md says how to add a regression.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz/fuzz_entries.hpp"
#include "geardyn/models/scene/scene_reader.hpp"

namespace geardyn {
namespace {

namespace fs = std::filesystem;

struct FuzzInput {
  std::string target;  // scene_reader | mesh_tables
  std::string kind;    // corpus | regressions
  fs::path path;
};

const fs::path kFuzzDir = fs::path(GEARDYN_SOURCE_DIR) / "tests" / "fuzz";
const std::vector<std::string> kTargets = {"scene_reader", "mesh_tables"};

std::string ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<FuzzInput> Inputs(const std::string& kind) {
  std::vector<FuzzInput> out;
  for (const std::string& target : kTargets) {
    const fs::path dir = kFuzzDir / kind / target;
    if (!fs::is_directory(dir)) continue;
    for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
      if (e.is_regular_file()) out.push_back({target, kind, e.path()});
    }
  }
  std::sort(out.begin(), out.end(),
            [](const FuzzInput& a, const FuzzInput& b) { return a.path < b.path; });
  return out;
}

std::vector<FuzzInput> AllInputs() {
  std::vector<FuzzInput> all = Inputs("corpus");
  const std::vector<FuzzInput> reg = Inputs("regressions");
  all.insert(all.end(), reg.begin(), reg.end());
  return all;
}

void RunEntry(const FuzzInput& in) {
  const std::string bytes = ReadBytes(in.path);
  const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
  if (in.target == "scene_reader") {
    fuzz::FuzzSceneReader(data, bytes.size());
  } else {
    fuzz::FuzzMeshTables(data, bytes.size());
  }
}

class FuzzRegressionTest : public ::testing::TestWithParam<FuzzInput> {};

// The contract: the entry returns normally; anything escaping (FuzzContractViolation,
// std::out_of_range, InternalError, bad_alloc, …) fails with its message.
TEST_P(FuzzRegressionTest, EntryReturnsNormally) {
  const FuzzInput& in = GetParam();
  try {
    RunEntry(in);
  } catch (const std::exception& e) {
    FAIL() << in.path << ": " << e.what();
  }
}

std::string Name(const ::testing::TestParamInfo<FuzzInput>& info) {
  std::string name =
      info.param.kind + "_" + info.param.target + "_" + info.param.path.stem().string();
  std::replace_if(
      name.begin(), name.end(), [](char c) { return !std::isalnum(c); }, '_');
  return name;
}

INSTANTIATE_TEST_SUITE_P(Inputs, FuzzRegressionTest, ::testing::ValuesIn(AllInputs()), Name);

// The seeds are valid scenes written from docs/scene-format.md (a seed the reader rejects would
// only teach the fuzzer error paths): ParseScene accepts each one, with its overrides.
TEST(FuzzCorpusTest, SeedsAreValidScenes) {
  const std::vector<FuzzInput> seeds = Inputs("corpus");
  for (const std::string& target : kTargets) {
    EXPECT_TRUE(std::any_of(seeds.begin(), seeds.end(),
                            [&](const FuzzInput& s) { return s.target == target; }))
        << "no seed for " << target;
  }
  for (const FuzzInput& seed : seeds) {
    const fuzz::SplitInput in = fuzz::SplitAtOverrideMarker(ReadBytes(seed.path));
    const std::string text =
        seed.target == "mesh_tables" ? fuzz::MeshTablesBaseScene() + in.scene_text : in.scene_text;
    EXPECT_NO_THROW(ParseScene(text, fuzz::kFuzzSource, in.overrides)) << seed.path;
  }
}

// The example seeds are the example scenes verbatim (the corpus must not drift from them).
TEST(FuzzCorpusTest, ExampleSeedsMatchTheExamples) {
  const fs::path examples = fs::path(GEARDYN_SOURCE_DIR) / "examples" / "scenes";
  int count = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(examples)) {
    const fs::path seed =
        kFuzzDir / "corpus" / "scene_reader" / ("example-" + e.path().filename().string());
    EXPECT_TRUE(fs::exists(seed)) << seed << " missing (copy " << e.path() << ")";
    if (fs::exists(seed)) {
      EXPECT_EQ(ReadBytes(seed), ReadBytes(e.path())) << seed;
    }
    ++count;
  }
  EXPECT_GT(count, 0);
}

// The marker splits the input: text before it, one override per non-empty line after it.
TEST(FuzzEntriesTest, SplitAtOverrideMarker) {
  const fuzz::SplitInput a = fuzz::SplitAtOverrideMarker("a = 1\n#--set\nx=1\n\r\ny.z=\"q\"\r\n");
  EXPECT_EQ(a.scene_text, "a = 1\n");
  EXPECT_EQ(a.overrides, (std::vector<std::string>{"x=1", "y.z=\"q\""}));
  const fuzz::SplitInput b = fuzz::SplitAtOverrideMarker("a = 1\n#--settle\n");
  EXPECT_EQ(b.scene_text, "a = 1\n#--settle\n");
  EXPECT_TRUE(b.overrides.empty());
  std::string many = "#--set\n";
  for (int i = 0; i < 40; ++i) many += "k=" + std::to_string(i) + "\n";
  EXPECT_EQ(fuzz::SplitAtOverrideMarker(many).overrides.size(), fuzz::kMaxOverrides);
}

}  // namespace
}  // namespace geardyn
