// The built-in scenes: the text of examples/scenes/NAME.toml, embedded at configure time
// (models/CMakeLists.txt generates builtin_scene_texts.inc), parsed by the ordinary reader.
#include "geardyn/models/scene/builtin_scenes.hpp"

#include <string_view>
#include <utility>

namespace geardyn {
namespace {

constexpr std::pair<std::string_view, std::string_view> kScenes[] = {
#include "builtin_scene_texts.inc"
};

}  // namespace

std::vector<std::string> BuiltinSceneNames() {
  std::vector<std::string> names;
  for (const auto& [name, text] : kScenes) names.emplace_back(name);
  return names;
}

std::optional<std::string_view> BuiltinSceneText(std::string_view name) {
  for (const auto& [scene_name, text] : kScenes) {
    if (scene_name == name) return text;
  }
  return std::nullopt;
}

}  // namespace geardyn
