/// @file
/// @brief Reading scene files (TOML, docs/scene-format.md) into a validated Scene, with
/// `--set path=value` overrides, and the SceneError every reading failure throws.
///
/// Every error names where it comes from as `FILE:LINE: KEY: REASON`, for example
/// `rig.toml:12: gear.wheel.teeth: must be a positive integer, got -5`. Keys use element names
/// where known (`gear.wheel.teeth`, `mesh.pinion-wheel.center_distance`) and the 0-based index
/// before a name is known (`gear[1]`). A value that came from an override has no line:
/// `rig.toml: --set gear.pinion.teeth=0: gear.pinion.teeth: must be a positive integer, got 0`.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "geardyn/models/scene/scene.hpp"

namespace geardyn {

/// @brief A scene that cannot be read: bad file, TOML syntax, bad override or failed validation.
class SceneError : public InvalidInput {
 public:
  /// @param[in] source file path or "builtin:NAME"
  /// @param[in] line 1-based line in `source`, 0 if unknown or the value came from an override
  /// @param[in] key dotted key path (may be empty when the error concerns the whole file)
  /// @param[in] reason what is wrong, with the value and the bound
  /// @param[in] override_spec the `--set` override the offending value came from, or empty
  SceneError(std::string source, int line, std::string key, std::string reason,
             std::string override_spec = {});

  const std::string& source() const { return source_; }
  int line() const { return line_; }
  const std::string& key() const { return key_; }
  const std::string& reason() const { return reason_; }
  /// The override text (e.g. "gear.pinion.teeth=0") the offending value came from, or empty.
  const std::string& override_spec() const { return override_spec_; }

 private:
  std::string source_;
  int line_;
  std::string key_;
  std::string reason_;
  std::string override_spec_;
};

/// @brief Reads, overrides and validates a scene.
/// @param[in] path_or_builtin a file path, or "builtin:NAME" for a built-in scene
///   (builtin_scenes.hpp)
/// @param[in] overrides `path=value` strings applied to the parsed TOML tree before validation
///   (see ParseScene)
/// @throws SceneError if the file cannot be read, the built-in does not exist, or ParseScene
///   fails; errors name the path as given (or "builtin:NAME").
Scene LoadScene(const std::string& path_or_builtin, const std::vector<std::string>& overrides = {});

/// @brief Parses, overrides and validates scene text.
///
/// Overrides (`--set`) have the form `path=value`. The path is dot-separated; an array of
/// tables element is selected by its `name` (a mesh without a name also by its default
/// "<pinion>-<gear>", a bearing or load by "bearing<i>"/"load<i>") or by its 0-based index:
/// `gear.pinion.teeth=23`, `gear.0.teeth=23`, `operating_point.torque=200`,
/// `mesh.pinion-wheel.center_distance=0.151`, `title="x"`. The value is parsed as a TOML value
/// (`23` is an integer, `0.151` a float, `[1, 2]` an array, `"x"` a string); text that is not a
/// TOML value is taken as a bare string (`hand=right`). Missing keys are added (and then checked
/// like any other key); missing tables on the way are created.
/// @param[in] toml_text the scene file's content
/// @param[in] source_name the name errors use for the text (a path, or "builtin:NAME")
/// @param[in] overrides `path=value` strings, applied in order
/// @throws SceneError on TOML syntax errors (with toml++'s line), malformed overrides (no '=',
///   empty path, unknown element name or index, path through a non-table) and every validation
///   failure (docs/scene-format.md lists the rules).
Scene ParseScene(std::string_view toml_text, const std::string& source_name,
                 const std::vector<std::string>& overrides = {});

}  // namespace geardyn
