// Scene reader: TOML text → overrides applied on the tree (overrides.cpp) → validated Scene (the
// section readers, section_readers.hpp). Errors are located by error_context.hpp.
#include "geardyn/models/scene/scene_reader.hpp"

#include <toml++/toml.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <utility>

#include "geardyn/models/scene/builtin_scenes.hpp"
#include "scene/error_context.hpp"
#include "scene/overrides.hpp"
#include "scene/section_readers.hpp"
#include "scene/speed_ratios.hpp"
#include "scene/suggestions.hpp"
#include "scene/toml_fields.hpp"

namespace geardyn {
namespace {

using internal::ErrorContext;

// An array of tables of the scene: its key, whether the scene needs at least one, and where a
// duplicate name is reported (the `name` key of a gear, which must be named; the table of the
// others, whose name may be a default).
struct Section {
  std::string_view kind;
  bool required = false;
  bool duplicate_at_name_key = false;
};

// Element name → its table, for error locations.
using TablesByName = std::map<std::string, const toml::table*>;

toml::table ParseToml(const ErrorContext& ctx, std::string_view text) {
  try {
    return toml::parse(text, ctx.source());
  } catch (const toml::parse_error& e) {
    throw SceneError(ctx.source(), static_cast<int>(e.source().begin.line), "",
                     "TOML syntax error: " + std::string(e.description()));
  }
}

// The array of tables under `key` ([[key]]), or nullptr if absent.
const toml::array* ArrayOfTables(const ErrorContext& ctx, const toml::table& root,
                                 std::string_view key) {
  const toml::node* n = root.get(key);
  if (n == nullptr) return nullptr;
  const std::string k(key);
  const toml::array* a = n->as_array();
  if (a == nullptr) {
    ctx.Fail(n, k, "must be an array of tables ([[" + k + "]]), got " + internal::Describe(*n));
  }
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node* e = a->get(i);
    if (!e->is_table()) {
      ctx.Fail(e, k + "[" + std::to_string(i) + "]",
               "must be a table ([[" + k + "]] or {...}), got " + internal::Describe(*e));
    }
  }
  return a;
}

// Reads every element of `section` with read(table, index) into `out`, rejecting duplicate
// names, and returns the tables by element name.
template <typename Def, typename Read>
TablesByName ReadSection(const ErrorContext& ctx, const toml::table& root, const Section& section,
                         const Read& read, std::vector<Def>* out) {
  const std::string kind(section.kind);
  const toml::array* array = ArrayOfTables(ctx, root, kind);
  if (section.required && (array == nullptr || array->empty())) {
    ctx.Fail(nullptr, kind,
             "the scene has no " + kind + " (at least one [[" + kind + "]] is required)");
  }
  TablesByName tables;
  if (array == nullptr) return tables;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const toml::table& t = *array->get(i)->as_table();
    Def def = read(t, i);
    if (const auto it = tables.find(def.name); it != tables.end()) {
      const int first = ctx.Line(it->second);
      ctx.Fail(section.duplicate_at_name_key ? t.get("name") : &t,
               kind + "[" + std::to_string(i) + "].name",
               "duplicate " + kind + " name '" + def.name + "'" +
                   (first > 0 ? " (first defined at line " + std::to_string(first) + ")" : ""));
    }
    tables.emplace(def.name, &t);
    out->push_back(std::move(def));
  }
  return tables;
}

// Kinematics: loops of meshes (and torsionally stiff bearings) must close.
void CheckKinematics(const ErrorContext& ctx, const Scene& scene, const TablesByName& mesh_tables,
                     const TablesByName& bearing_tables, const TablesByName& shaft_tables,
                     const std::vector<const toml::table*>& planetary_tables) {
  const internal::SpeedRatios ratios = internal::CalcSpeedRatios(scene, scene.operating_point.body);
  if (!ratios.conflict_mesh && !ratios.conflict_bearing && !ratios.conflict_shaft) return;
  const bool is_mesh = ratios.conflict_mesh.has_value();
  const toml::table* t = nullptr;
  std::string key, what;
  if (ratios.conflict_shaft) {
    const std::string& name = scene.shafts[*ratios.conflict_shaft].name;
    t = shaft_tables.at(name);
    key = "shaft." + name;
    what = "shaft (its gears turn with it)";
  } else {
    const std::string name = is_mesh ? scene.meshes[*ratios.conflict_mesh].name
                                     : scene.bearings[*ratios.conflict_bearing].name;
    if (const auto planetary = scene.FindPlanetaryMesh(name); is_mesh && planetary) {
      const auto& sets = scene.planetaries;
      t = planetary_tables[static_cast<std::size_t>(planetary->first - sets.data())];
    } else {
      t = is_mesh ? mesh_tables.at(name) : bearing_tables.at(name);
    }
    key = (is_mesh ? "mesh." : "bearing.") + name;
    what = is_mesh ? "mesh" : "torsional coupling";
  }
  ctx.Fail(t, key,
           "kinematically locked loop: through the other elements gear '" + ratios.conflict_gear +
               "' turns at " + internal::FormatNumber(ratios.ratio_known) +
               " x the reference speed, but this " + what + " requires " +
               internal::FormatNumber(ratios.ratio_implied) + " x");
}

Scene Validate(const ErrorContext& ctx, const toml::table& root) {
  Scene scene;
  scene.source = ctx.source();
  const internal::Fields top(ctx, root, "");
  if (const toml::node* osc = root.get("oscillator")) {
    // An oscillator scene: the [oscillator] table alone (and a title).
    for (const char* key : {"gear", "mesh", "planetary", "bearing", "load", "operating_point",
                            "damping", "shaft", "planar"}) {
      if (root.get(key) != nullptr) {
        ctx.Fail(root.get(key), key,
                 "an oscillator scene ([oscillator]) is the dimensionless oscillator alone and "
                 "takes no '" +
                     std::string(key) + "' (remove it, or the [oscillator] table)");
      }
    }
    top.CheckKnown({"title", "oscillator"});
    if (auto title = top.OptString("title")) scene.title = *title;
    const toml::table* t = osc->as_table();
    if (t == nullptr) {
      ctx.Fail(osc, "oscillator",
               "must be a table ([oscillator]), got " + internal::Describe(*osc));
    }
    scene.oscillator = internal::ReadOscillator(ctx, *t);
    return scene;
  }
  top.CheckKnown({"title", "planar", "gear", "mesh", "planetary", "bearing", "load",
                  "operating_point", "damping", "shaft", "oscillator"});
  if (auto title = top.OptString("title")) scene.title = *title;
  if (auto planar = top.OptBool("planar")) scene.planar = *planar;

  ReadSection(
      ctx, root, {"gear", true, true},
      [&](const toml::table& t, std::size_t i) { return internal::ReadGear(ctx, t, i); },
      &scene.gears);
  const TablesByName mesh_tables = ReadSection(
      ctx, root, {"mesh", true, false},
      [&](const toml::table& t, std::size_t i) { return internal::ReadMesh(ctx, t, i, scene); },
      &scene.meshes);
  // [[planetary]] sets expand into gears and meshes before the bearings and loads refer to them.
  std::vector<const toml::table*> planetary_tables;
  if (const toml::array* sets = ArrayOfTables(ctx, root, "planetary")) {
    for (std::size_t i = 0; i < sets->size(); ++i) {
      const toml::table& t = *sets->get(i)->as_table();
      internal::ReadPlanetary(ctx, t, i, &scene);
      planetary_tables.push_back(&t);
    }
  }
  const TablesByName shaft_tables = ReadSection(
      ctx, root, {"shaft", false, true},
      [&](const toml::table& t, std::size_t i) { return internal::ReadShaft(ctx, t, i, scene); },
      &scene.shafts);
  const TablesByName bearing_tables = ReadSection(
      ctx, root, {"bearing", false, false},
      [&](const toml::table& t, std::size_t i) { return internal::ReadBearing(ctx, t, i, scene); },
      &scene.bearings);
  ReadSection(
      ctx, root, {"load", false, false},
      [&](const toml::table& t, std::size_t i) { return internal::ReadLoad(ctx, t, i, scene); },
      &scene.loads);

  internal::AddPlanetBearings(ctx, planetary_tables, &scene);
  internal::PlaceShaftNodes(&scene);
  if (scene.planar && !scene.shafts.empty()) {
    ctx.Fail(root.get("planar"), "planar",
             "a scene with [[shaft]] cannot be planar: shaft bending needs the tilts rx, ry that "
             "the planar model holds fixed");
  }
  scene.operating_point = internal::ReadOperatingPoint(ctx, root, scene);
  scene.damping = internal::ReadSystemDamping(ctx, root);
  internal::CheckPlanetaryOperatingPoint(ctx, planetary_tables, scene);
  CheckKinematics(ctx, scene, mesh_tables, bearing_tables, shaft_tables, planetary_tables);
  return scene;
}

}  // namespace

Scene ParseScene(std::string_view toml_text, const std::string& source_name,
                 const std::vector<std::string>& overrides) {
  ErrorContext ctx(source_name);
  toml::table root = ParseToml(ctx, toml_text);
  for (std::size_t i = 0; i < overrides.size(); ++i) {
    internal::ApplyOverride(ctx, root, i, overrides[i]);
  }
  return Validate(ctx, root);
}

Scene LoadScene(const std::string& path_or_builtin, const std::vector<std::string>& overrides) {
  constexpr std::string_view kBuiltin = "builtin:";
  if (path_or_builtin.rfind(kBuiltin, 0) == 0) {
    const std::string name = path_or_builtin.substr(kBuiltin.size());
    const std::optional<std::string_view> text = BuiltinSceneText(name);
    if (!text) {
      const std::vector<std::string> names = BuiltinSceneNames();
      throw SceneError(path_or_builtin, 0, "",
                       "no built-in scene named '" + name + "'" +
                           internal::DidYouMean(name, names) +
                           "; built-in scenes: " + internal::JoinNames(names));
    }
    return ParseScene(*text, path_or_builtin, overrides);
  }
  std::error_code ec;
  if (std::filesystem::is_directory(path_or_builtin, ec)) {
    throw SceneError(path_or_builtin, 0, "", "is a directory, not a scene file");
  }
  std::ifstream in(path_or_builtin, std::ios::binary);
  if (!in) {
    throw SceneError(path_or_builtin, 0, "",
                     "cannot open the scene file (missing or unreadable); built-in scenes are "
                     "named builtin:NAME");
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw SceneError(path_or_builtin, 0, "", "error while reading the scene file");
  return ParseScene(text.str(), path_or_builtin, overrides);
}

}  // namespace geardyn
