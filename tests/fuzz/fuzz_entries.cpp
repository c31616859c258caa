// The per-input logic of the fuzz targets (fuzz_entries.hpp): read, build, check the contract.
#include "fuzz/fuzz_entries.hpp"

#include <cmath>
#include <string_view>

#include "geardyn/common/errors.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"

namespace geardyn::fuzz {
namespace {

// A spur pair 20/40 without bearings or loads, its [[mesh]] last so that appended text lands in
// the mesh table (FuzzMeshTables).
constexpr const char* kMeshTablesBase = R"toml(title = "fuzz base: spur pair 20/40"
[[gear]]
name = "pinion"
teeth = 20
normal_module = 0.003
normal_pressure_angle_deg = 20.0
face_width = 0.02
mass = 0.5
inertia = 2e-4

[[gear]]
name = "wheel"
teeth = 40
normal_module = 0.003
normal_pressure_angle_deg = 20.0
face_width = 0.02
mass = 2.0
inertia = 3e-3

[operating_point]
speed_rpm = 1500.0
torque = 100.0

[[mesh]]
pinion = "pinion"
gear = "wheel"
)toml";

template <typename Matrix>
void RequireFinite(const Matrix& m, const char* what) {
  if (!m.allFinite()) throw FuzzContractViolation(std::string("non-finite entry in ") + what);
}

void RequireFinite(const SparseMatrix& m, const char* what) {
  for (int k = 0; k < m.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(m, k); it; ++it) {
      if (!std::isfinite(it.value())) {
        throw FuzzContractViolation(std::string("non-finite entry in ") + what);
      }
    }
  }
}

// The reader's contract for an InvalidInput: the message names the source.
void RequireNamesSource(const InvalidInput& e) {
  if (std::string_view(e.what()).find(kFuzzSource) == std::string_view::npos) {
    throw FuzzContractViolation(std::string("InvalidInput without the source name '") +
                                kFuzzSource + "': " + e.what());
  }
}

void ReadAndBuild(const std::string& scene_text, const std::vector<std::string>& overrides) {
  Scene scene;
  try {
    scene = ParseScene(scene_text, kFuzzSource, overrides);
  } catch (const InvalidInput& e) {
    RequireNamesSource(e);
    return;
  }
  // As `simulate` builds it: contact meshes allowed, transmission error tabulated.
  SceneSystemOptions options;
  options.allow_contact_meshes = true;
  options.analysis = "fuzz";
  try {
    const SceneSystem built = BuildSceneSystem(scene, options);
    const SystemModel& model = built.model;
    RequireFinite(model.mass(), "the mass matrix");
    RequireFinite(model.constant_stiffness(), "the constant stiffness");
    RequireFinite(model.constant_damping(), "the constant damping");
    RequireFinite(model.constant_load(), "the constant load");
    for (const SystemMesh& mesh : model.meshes()) {
      RequireFinite(mesh.G, "a mesh Jacobian G");
      RequireFinite(mesh.mean_core_stiffness, "a mesh mean stiffness");
      if (!std::isfinite(mesh.equivalent_mass) || !std::isfinite(mesh.damping_coefficient) ||
          !std::isfinite(mesh.phase_ratio) || !std::isfinite(mesh.phase_offset)) {
        throw FuzzContractViolation("non-finite mass, damping or phase of mesh " + mesh.name);
      }
    }
  } catch (const InvalidInput& e) {
    if (std::string_view(e.what()).empty()) {
      throw FuzzContractViolation("BuildSceneSystem threw InvalidInput with an empty message");
    }
  }
}

}  // namespace

SplitInput SplitAtOverrideMarker(const std::string& text) {
  SplitInput out;
  const std::string_view marker(kOverrideMarker);
  std::size_t line_start = 0;
  while (line_start <= text.size()) {
    std::size_t line_end = text.find('\n', line_start);
    if (line_end == std::string::npos) line_end = text.size();
    std::string_view line(text.data() + line_start, line_end - line_start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line == marker) {
      out.scene_text = text.substr(0, line_start);
      std::size_t pos = line_end + 1;
      while (pos < text.size() && out.overrides.size() < kMaxOverrides) {
        std::size_t end = text.find('\n', pos);
        if (end == std::string::npos) end = text.size();
        std::string o = text.substr(pos, end - pos);
        if (!o.empty() && o.back() == '\r') o.pop_back();
        if (!o.empty()) out.overrides.push_back(std::move(o));
        pos = end + 1;
      }
      return out;
    }
    line_start = line_end + 1;
  }
  out.scene_text = text;
  return out;
}

void FuzzSceneReader(const std::uint8_t* data, std::size_t size) {
  const SplitInput in =
      SplitAtOverrideMarker(std::string(reinterpret_cast<const char*>(data), size));
  ReadAndBuild(in.scene_text, in.overrides);
}

void FuzzMeshTables(const std::uint8_t* data, std::size_t size) {
  const SplitInput in =
      SplitAtOverrideMarker(std::string(reinterpret_cast<const char*>(data), size));
  ReadAndBuild(kMeshTablesBase + in.scene_text, in.overrides);
}

const char* MeshTablesBaseScene() { return kMeshTablesBase; }

}  // namespace geardyn::fuzz
