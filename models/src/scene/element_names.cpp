// Element names of a scene: defaults, key-path prefixes, validation and gear references.
#include "scene/element_names.hpp"

#include <algorithm>
#include <cctype>
#include <optional>
#include <vector>

#include "scene/suggestions.hpp"

namespace geardyn::internal {
namespace {

// Valid element names: letters, digits, '_' and '-', not starting with a digit (so that
// `--set gear.NAME.key=...` and `--set gear.INDEX.key=...` cannot be confused).
bool IsValidName(std::string_view s) {
  if (s.empty() || std::isdigit(static_cast<unsigned char>(s.front())) != 0) return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-';
  });
}

const char* const kNameRule = "letters, digits, '_' and '-', not starting with a digit";

std::string IndexedPrefix(std::string_view kind, std::size_t index) {
  return std::string(kind) + "[" + std::to_string(index) + "]";
}

}  // namespace

std::string DefaultElementName(std::string_view kind, const toml::table& t, std::size_t index) {
  if (kind == "mesh") {
    const auto* p = t.get_as<std::string>("pinion");
    const auto* g = t.get_as<std::string>("gear");
    return p != nullptr && g != nullptr ? p->get() + "-" + g->get() : std::string();
  }
  if (kind == "bearing" || kind == "load" || kind == "planetary") {
    return std::string(kind) + std::to_string(index);
  }
  return {};
}

std::string ElementPrefix(const toml::table& t, std::string_view kind, std::size_t index) {
  std::string name = DefaultElementName(kind, t, index);
  if (const toml::node* n = t.get("name")) {
    name = n->is_string() ? n->as_string()->get() : std::string();
  }
  return IsValidName(name) ? std::string(kind) + "." + name : IndexedPrefix(kind, index);
}

void CheckElementKeys(const ErrorContext& ctx, const toml::table& t, std::string_view kind,
                      std::size_t index, std::initializer_list<std::string_view> allowed) {
  Fields(ctx, t, ElementPrefix(t, kind, index)).CheckKnown(allowed);
}

std::string ReadElementName(const ErrorContext& ctx, const toml::table& t, std::string_view kind,
                            std::size_t index) {
  const Fields indexed(ctx, t, IndexedPrefix(kind, index));
  std::optional<std::string> name = indexed.OptString("name");
  if (!name) {
    std::string default_name = DefaultElementName(kind, t, index);
    if (default_name.empty()) {
      indexed.Missing("name", "a unique name (" + std::string(kNameRule) + ")");
    }
    return default_name;
  }
  if (!IsValidName(*name)) {
    indexed.Fail("name", "'" + *name + "' is not a valid name (" + kNameRule + ")");
  }
  return *name;
}

const GearDef& GearByName(const Fields& f, std::string_view key, const std::string& name,
                          const Scene& scene) {
  for (const GearDef& g : scene.gears) {
    if (g.name == name) return g;
  }
  std::vector<std::string> names;
  for (const GearDef& g : scene.gears) names.push_back(g.name);
  f.Fail(key,
         "no gear named '" + name + "'" + DidYouMean(name, names) + "; gears: " + JoinNames(names));
}

std::string ReadGearName(const Fields& f, std::string_view key, const std::string& what,
                         const Scene& scene) {
  std::string name = f.ReqString(key, what);
  (void)GearByName(f, key, name, scene);
  return name;
}

}  // namespace geardyn::internal
