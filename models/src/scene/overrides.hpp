/// @file
/// @brief `--set PATH=VALUE` overrides applied to a scene's TOML tree before validation
/// (internal to the scene reader; the syntax is documented at ParseScene).
#pragma once

#include <toml++/toml.h>

#include <cstddef>
#include <string>

#include "scene/error_context.hpp"

namespace geardyn::internal {

/// @brief Parses override number `index`, `text` = "PATH=VALUE", and splices its value into
/// `root` (creating missing tables on the way). The new value's source is the override, which
/// `ctx` registers, so later errors about it name the override.
/// @throws SceneError (located at the override) if the text is malformed or the path selects no
///   element or runs through a non-table.
void ApplyOverride(ErrorContext& ctx, toml::table& root, std::size_t index,
                   const std::string& text);

}  // namespace geardyn::internal
