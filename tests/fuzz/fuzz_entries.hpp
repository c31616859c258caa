/// @file
/// @brief The per-input logic of the fuzz targets (issue 16, "geardyn never returns garbage"),
/// shared by the libFuzzer executables (tests/fuzz/*_fuzz.cpp) and the regression gtest
/// (tests/models/scene/fuzz_regressions_test.cpp), so that a saved crash input replays the
/// exact code the fuzzer ran.
///
/// The contract checked, for any bytes: the reader either returns a Scene or throws
/// geardyn::InvalidInput whose message names the source; a Scene it returns either builds a
/// SystemModel (BuildSceneSystem) whose matrices and loads are finite, or BuildSceneSystem throws
/// InvalidInput with a message. Each entry returns normally in those cases. A broken contract
/// throws FuzzContractViolation; any other exception (std::out_of_range, InternalError,
/// bad_alloc, toml::parse_error…) escapes as it is. Crashes, UB and leaks are the sanitizers'.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace geardyn::fuzz {

/// @brief Thrown when a reader returned normally but broke the contract (a message that does
/// not name the source, a non-finite number in the built model).
class FuzzContractViolation : public std::logic_error {
 public:
  explicit FuzzContractViolation(const std::string& what) : std::logic_error(what) {}
};

/// The marker line that ends the scene text; each following non-empty line is one `--set`
/// override `path=value` (at most kMaxOverrides). A TOML comment, so seeds stay valid scenes.
inline constexpr const char* kOverrideMarker = "#--set";
inline constexpr std::size_t kMaxOverrides = 16;

/// The source name the entries give the reader (errors must name it).
inline constexpr const char* kFuzzSource = "fuzz.toml";

/// @brief A fuzz input split at the marker line: the scene text and the overrides.
struct SplitInput {
  std::string scene_text;
  std::vector<std::string> overrides;
};

/// @brief Splits `text` at the first line equal to kOverrideMarker (see there).
SplitInput SplitAtOverrideMarker(const std::string& text);

/// @brief Target scene_reader: the bytes are a scene file with optional `--set` overrides after
/// the marker line; ParseScene, then BuildSceneSystem (contact meshes allowed, transmission
/// error built, as `simulate` does).
void FuzzSceneReader(const std::uint8_t* data, std::size_t size);

/// @brief Target mesh_tables: the user tables of one mesh. The bytes are appended to a fixed
/// valid spur-pair scene that ends in its [[mesh]] table, so they are the mesh's keys and
/// sub-tables ([mesh.parameters] tables and Fourier series, [mesh.modifications],
/// [mesh.errors], [mesh.contact]); then as FuzzSceneReader (overrides after the marker too).
void FuzzMeshTables(const std::uint8_t* data, std::size_t size);

/// @brief The fixed scene text FuzzMeshTables appends its input to.
const char* MeshTablesBaseScene();

}  // namespace geardyn::fuzz
