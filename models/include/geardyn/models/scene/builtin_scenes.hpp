/// @file
/// @brief Scenes compiled into the library as TOML text, loadable as "builtin:NAME".
///
/// Each built-in scene is the same text as the file examples/scenes/NAME.toml (a test checks
/// that they agree) and is parsed by the same reader as any file: LoadScene("builtin:NAME").
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace geardyn {

/// @brief Names of the built-in scenes, sorted: "helical-pair", "kahraman-blankenship-rig".
std::vector<std::string> BuiltinSceneNames();

/// @brief TOML text of the built-in scene `name` (without the "builtin:" prefix), or nullopt.
/// The view refers to static storage.
std::optional<std::string_view> BuiltinSceneText(std::string_view name);

}  // namespace geardyn
