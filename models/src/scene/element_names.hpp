/// @file
/// @brief Names of a scene's elements ([[gear]], [[mesh]], [[bearing]], [[load]]): their default
/// names, key-path prefixes, validation and references to gears by name (internal to the scene
/// reader).
///
/// The override paths (`--set mesh.NAME.key=...`) and the reader share these rules, so an element
/// is found under the name the reader gives it.
#pragma once

#include <toml++/toml.h>

#include <cstddef>
#include <initializer_list>
#include <string>
#include <string_view>

#include "geardyn/models/scene/scene.hpp"
#include "scene/error_context.hpp"
#include "scene/toml_fields.hpp"

namespace geardyn::internal {

/// @brief The name element `index` of [[kind]] gets when it has no `name` key: "<pinion>-<gear>"
/// for a mesh whose pinion and gear are strings, "bearing<i>" / "load<i>" / "planetary<i>", else
/// empty (a gear
/// must be named).
std::string DefaultElementName(std::string_view kind, const toml::table& t, std::size_t index);

/// @brief Key path prefix of an element: "kind.NAME" if its name (given, or the default) is
/// known and valid, else "kind[i]".
std::string ElementPrefix(const toml::table& t, std::string_view kind, std::size_t index);

/// @brief Rejects any key of element `index` of [[kind]] that is not in `allowed` (errors name
/// the element by its ElementPrefix).
void CheckElementKeys(const ErrorContext& ctx, const toml::table& t, std::string_view kind,
                      std::size_t index, std::initializer_list<std::string_view> allowed);

/// @brief The element's `name`, or its default name if absent.
/// @throws SceneError at "kind[i].name" if the name is not a valid name (letters, digits, '_'
///   and '-', not starting with a digit), or missing without a default.
std::string ReadElementName(const ErrorContext& ctx, const toml::table& t, std::string_view kind,
                            std::size_t index);

/// @brief The scene's gear named `name`, which the table of `f` references under `key`.
/// @throws SceneError at `key` if there is none, with a hint and the list of gears.
const GearDef& GearByName(const Fields& f, std::string_view key, const std::string& name,
                          const Scene& scene);

/// @brief Reads the gear name under `key` (required) and checks that the scene has that gear.
std::string ReadGearName(const Fields& f, std::string_view key, const std::string& what,
                         const Scene& scene);

}  // namespace geardyn::internal
