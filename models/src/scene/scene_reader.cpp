// Scene reader: TOML text → overrides applied on the tree → validated Scene.
//
// Locations: every toml++ node carries source().begin.line and source().path. The scene text is
// parsed with path = the source name; each override value is parsed from its own little TOML
// document whose path is a private marker ("--set#<i>"). Moving a node keeps its source, so after
// the overrides are spliced into the tree, a node's path tells whether it came from the file
// (report FILE:LINE) or from an override (report FILE: --set TEXT).
#include "geardyn/models/scene/scene_reader.hpp"

#include <toml++/toml.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <utility>

#include "geardyn/common/units.hpp"
#include "geardyn/models/scene/builtin_scenes.hpp"
#include "scene/speed_ratios.hpp"

namespace geardyn {
namespace {

std::string FormatWhat(const std::string& source, int line, const std::string& key,
                       const std::string& reason, const std::string& override_spec) {
  std::string out = source;
  if (line > 0) {
    out += ":" + std::to_string(line);
  } else if (!override_spec.empty()) {
    out += ": --set " + override_spec;
  }
  out += ": ";
  if (!key.empty()) out += key + ": ";
  return out + reason;
}

// ---------------------------------------------------------------------------------------------
// Small text helpers.

// Shortest round-trip representation ("0.003", "1e+10", "inf", "nan").
std::string Num(double v) {
  std::array<char, 64> buf{};
  const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return std::string(buf.data(), res.ptr);
}

// An angle in radians shown in degrees, rounded to 10 significant digits (hides the rounding of
// the degree → radian → degree round trip).
std::string Deg(double rad) {
  std::array<char, 64> buf{};
  std::snprintf(buf.data(), buf.size(), "%.10g", RadToDeg(rad));
  return std::string(buf.data()) + " deg";
}

std::string Trim(std::string_view s) {
  const auto is_space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return std::string(s);
}

std::vector<std::string> Split(std::string_view s, char sep) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t pos = s.find(sep, start);
    out.emplace_back(Trim(s.substr(start, pos == std::string_view::npos ? pos : pos - start)));
    if (pos == std::string_view::npos) return out;
    start = pos + 1;
  }
}

bool IsIndex(std::string_view s) {
  return !s.empty() && s.size() <= 9 &&
         std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

std::size_t EditDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> prev(b.size() + 1);
  std::vector<std::size_t> cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t subst = prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, subst});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

// The closest candidate by edit distance (or a prefix relation, as in "speed" → "speed_rpm"),
// if it is close enough to be a plausible typo; empty otherwise.
template <typename Range>
std::string Closest(std::string_view word, const Range& candidates) {
  std::string best;
  std::size_t best_distance = std::numeric_limits<std::size_t>::max();
  for (const auto& candidate_ref : candidates) {
    const std::string_view candidate(candidate_ref);
    std::size_t d = EditDistance(word, candidate);
    const std::size_t limit = std::max<std::size_t>(2, word.size() / 3);
    const bool prefix = word.size() >= 3 && (candidate.substr(0, word.size()) == word ||
                                             word.substr(0, candidate.size()) == candidate);
    if (d > limit && !prefix) continue;
    if (prefix) d = std::min<std::size_t>(d, limit);
    if (d < best_distance) {
      best_distance = d;
      best = std::string(candidate);
    }
  }
  return best;
}

template <typename Range>
std::string DidYouMean(std::string_view word, const Range& candidates) {
  const std::string best = Closest(word, candidates);
  return best.empty() ? std::string() : " (did you mean '" + best + "'?)";
}

template <typename Range>
std::string JoinNames(const Range& names) {
  std::string out;
  for (const auto& n : names) {
    if (!out.empty()) out += ", ";
    out += std::string_view(n);
  }
  return out.empty() ? std::string("none") : out;
}

// A TOML basic string literal holding `s`.
std::string QuoteToml(std::string_view s) {
  std::string out = "\"";
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (u < 0x20 || u == 0x7f) {
      std::array<char, 8> buf{};
      std::snprintf(buf.data(), buf.size(), "\\u%04x", static_cast<unsigned>(u));
      out += buf.data();
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// "got ..." text for a value of the wrong type.
std::string Describe(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string: {
      std::string s = n.as_string()->get();
      if (s.size() > 40) s = s.substr(0, 37) + "...";
      return "string \"" + s + "\"";
    }
    case toml::node_type::integer:
      return std::to_string(n.as_integer()->get()) + " (an integer)";
    case toml::node_type::floating_point:
      return Num(n.as_floating_point()->get()) + " (a float)";
    case toml::node_type::boolean:
      return std::string("boolean ") + (n.as_boolean()->get() ? "true" : "false");
    case toml::node_type::array:
      return "an array";
    case toml::node_type::table:
      return "a table";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    case toml::node_type::none:
      break;
  }
  return "nothing";
}

// Valid element names: letters, digits, '_' and '-', not starting with a digit (so that
// `--set gear.NAME.key=...` and `--set gear.INDEX.key=...` cannot be confused).
bool IsValidName(std::string_view s) {
  if (s.empty() || std::isdigit(static_cast<unsigned char>(s.front())) != 0) return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-';
  });
}

const char* const kNameRule = "letters, digits, '_' and '-', not starting with a digit";

constexpr std::array<const char*, 6> kDofNames = {"x", "y", "z", "rx", "ry", "rz"};

// ---------------------------------------------------------------------------------------------
// Where a node came from, and failing there.

class Context {
 public:
  explicit Context(std::string source) : source_(std::move(source)) {}

  const std::string& source() const { return source_; }

  // Registers the source-path marker of override number `index` and returns it.
  std::string AddOverride(std::size_t index, const std::string& text) {
    std::string marker = "--set#" + std::to_string(index);
    overrides_[marker] = text;
    return marker;
  }

  // Line of `node` in the file (0 if unknown or from an override) and the override it came from.
  std::pair<int, std::string> Where(const toml::node* node) const {
    if (node == nullptr) return {0, {}};
    const toml::source_region& src = node->source();
    if (src.path) {
      const auto it = overrides_.find(*src.path);
      if (it != overrides_.end()) return {0, it->second};
    }
    return {static_cast<int>(src.begin.line), {}};
  }

  int Line(const toml::node* node) const { return Where(node).first; }

  [[noreturn]] void Fail(const toml::node* where, const std::string& key,
                         const std::string& reason) const {
    auto [line, override_spec] = Where(where);
    throw SceneError(source_, line, key, reason, std::move(override_spec));
  }

  [[noreturn]] void FailOverride(const std::string& override_spec, const std::string& key,
                                 const std::string& reason) const {
    throw SceneError(source_, 0, key, reason, override_spec);
  }

 private:
  std::string source_;
  std::map<std::string, std::string> overrides_;  // source-path marker → override text
};

// A number read from the tree, with the node it came from (for error locations).
struct Number {
  double value = 0.0;
  const toml::node* node = nullptr;
};

// Typed access to the keys of one table, with `prefix` the key path of the table
// ("gear.wheel", "gear[1]", "operating_point").
class Fields {
 public:
  Fields(const Context& ctx, const toml::table& table, std::string prefix)
      : ctx_(ctx), table_(table), prefix_(std::move(prefix)) {}

  std::string Key(std::string_view key) const {
    return prefix_.empty() ? std::string(key) : prefix_ + "." + std::string(key);
  }
  const toml::node* Find(std::string_view key) const { return table_.get(key); }
  const toml::table& table() const { return table_; }

  [[noreturn]] void Fail(std::string_view key, const std::string& reason) const {
    ctx_.Fail(Find(key), Key(key), reason);
  }

  // Rejects any key not in `allowed` (the first such key in file order).
  void CheckKnown(std::initializer_list<std::string_view> allowed) const {
    const toml::node* worst = nullptr;
    std::string worst_key;
    int worst_line = std::numeric_limits<int>::max();
    for (const auto& [k, v] : table_) {
      if (std::find(allowed.begin(), allowed.end(), k.str()) != allowed.end()) continue;
      // Overridden values have line 0: report file keys first, in file order.
      int line = ctx_.Line(&v);
      if (line == 0) line = std::numeric_limits<int>::max() - 1;
      if (line < worst_line) {
        worst_line = line;
        worst = &v;
        worst_key = std::string(k.str());
      }
    }
    if (worst == nullptr) return;
    std::string hint = DidYouMean(worst_key, allowed);
    if (hint.empty()) hint = "; allowed keys: " + JoinNames(allowed);
    ctx_.Fail(worst, Key(worst_key), "unknown key" + hint);
  }

  [[noreturn]] void Missing(std::string_view key, const std::string& what) const {
    ctx_.Fail(&table_, Key(key), "missing (required: " + what + ")");
  }

  std::optional<Number> OptNumber(std::string_view key) const {
    const toml::node* n = Find(key);
    if (n == nullptr) return std::nullopt;
    double v = 0.0;
    if (const auto* i = n->as_integer()) {
      v = static_cast<double>(i->get());
    } else if (const auto* f = n->as_floating_point()) {
      v = f->get();
    } else {
      Fail(key, "must be a number, got " + Describe(*n));
    }
    if (!std::isfinite(v)) Fail(key, "must be finite, got " + Num(v));
    return Number{v, n};
  }

  Number ReqNumber(std::string_view key, const std::string& what) const {
    std::optional<Number> n = OptNumber(key);
    if (!n) Missing(key, what);
    return *n;
  }

  // Positive integer (tooth counts) in [1, max].
  int ReqPositiveInt(std::string_view key, const std::string& what, std::int64_t max) const {
    const toml::node* n = Find(key);
    if (n == nullptr) Missing(key, what);
    const auto* i = n->as_integer();
    if (i == nullptr) Fail(key, "must be a positive integer, got " + Describe(*n));
    const std::int64_t v = i->get();
    if (v <= 0) Fail(key, "must be a positive integer, got " + std::to_string(v));
    if (v > max) Fail(key, "must be at most " + std::to_string(max) + ", got " + std::to_string(v));
    return static_cast<int>(v);
  }

  std::optional<std::string> OptString(std::string_view key) const {
    const toml::node* n = Find(key);
    if (n == nullptr) return std::nullopt;
    const auto* s = n->as_string();
    if (s == nullptr) Fail(key, "must be a string, got " + Describe(*n));
    return s->get();
  }

  std::string ReqString(std::string_view key, const std::string& what) const {
    std::optional<std::string> s = OptString(key);
    if (!s) Missing(key, what);
    return *s;
  }

  std::optional<bool> OptBool(std::string_view key) const {
    const toml::node* n = Find(key);
    if (n == nullptr) return std::nullopt;
    const auto* b = n->as_boolean();
    if (b == nullptr) Fail(key, "must be a boolean (true or false), got " + Describe(*n));
    return b->get();
  }

  // Bound checks on a number read from this table.
  void Positive(std::string_view key, const Number& n) const {
    if (!(n.value > 0.0)) Fail(key, "must be > 0, got " + Num(n.value));
  }
  void NonNegative(std::string_view key, const Number& n) const {
    if (!(n.value >= 0.0)) Fail(key, "must be >= 0, got " + Num(n.value));
  }
  // A length in metres with a plausibility upper bound (catches millimetres given as metres).
  void Metres(std::string_view key, const Number& n, double max) const {
    Positive(key, n);
    if (n.value > max) {
      Fail(key, "must be at most " + Num(max) + " m (lengths are in metres: 3 mm is 0.003), got " +
                    Num(n.value));
    }
  }

 private:
  const Context& ctx_;
  const toml::table& table_;
  std::string prefix_;
};

// ---------------------------------------------------------------------------------------------
// The reader.

// Plausibility bounds (documented in docs/scene-format.md).
constexpr std::int64_t kMaxTeeth = 10000;
constexpr double kMaxModule = 0.1;     // m
constexpr double kMaxFaceWidth = 2.0;  // m
constexpr double kMaxPressureAngleDeg = 45.0;
constexpr double kMaxHelixAngleDeg = 45.0;
// Relative tolerances: equal data typed twice parse to identical doubles; this only absorbs the
// rounding of the degree → radian conversion and of hand-typed symmetric matrices.
constexpr double kEqualTol = 1e-9;
constexpr double kSymmetryTol = 1e-9;
constexpr double kPsdTol = 1e-9;  // on the diagonally scaled matrix (unit diagonal)

class Reader {
 public:
  explicit Reader(std::string source) : ctx_(std::move(source)) {}

  void Parse(std::string_view text) {
    try {
      root_ = toml::parse(text, ctx_.source());
    } catch (const toml::parse_error& e) {
      throw SceneError(ctx_.source(), static_cast<int>(e.source().begin.line), "",
                       "TOML syntax error: " + std::string(e.description()));
    }
  }

  void ApplyOverride(std::size_t index, const std::string& text);
  Scene Validate();

 private:
  toml::node* StepInto(toml::node* current, const std::string& segment, const std::string& walked,
                       const std::string& parent_key, const std::string& text,
                       const std::string& marker);
  std::size_t FindElement(const toml::array& array, const std::string& segment,
                          const std::string& walked, const std::string& array_key,
                          const std::string& text) const;

  const toml::array* ArrayOfTables(std::string_view key) const;
  GearDef ReadGear(const toml::table& t, std::size_t index);
  MeshDef ReadMesh(const toml::table& t, std::size_t index, const Scene& scene);
  BearingDef ReadBearing(const toml::table& t, std::size_t index, const Scene& scene);
  TorqueLoadDef ReadLoad(const toml::table& t, std::size_t index, const Scene& scene);
  OperatingPointDef ReadOperatingPoint(const Scene& scene);
  Matrix6 ReadMatrix6(const Fields& f, std::string_view key, const std::string& what) const;
  const GearDef& GearRef(const Fields& f, std::string_view key, const std::string& name,
                         const Scene& scene) const;
  static std::string ReadName(const Fields& indexed, bool required, std::string default_name);

  Context ctx_;
  toml::table root_;
};

// --- overrides -------------------------------------------------------------------------------

std::size_t Reader::FindElement(const toml::array& array, const std::string& segment,
                                const std::string& walked, const std::string& array_key,
                                const std::string& text) const {
  if (IsIndex(segment)) {
    const std::size_t index = std::stoul(segment);
    if (index >= array.size()) {
      ctx_.FailOverride(text, walked + "." + segment,
                        "no element " + segment + " ('" + walked + "' has " +
                            std::to_string(array.size()) + " elements, indices start at 0)");
    }
    return index;
  }
  std::vector<std::string> names;
  std::optional<std::size_t> found;
  for (std::size_t i = 0; i < array.size(); ++i) {
    const toml::table* t = array.get(i)->as_table();
    if (t == nullptr) continue;
    std::string name;
    if (const auto* n = t->get_as<std::string>("name")) {
      name = n->get();
    } else if (array_key == "mesh") {  // default names, as the reader gives them
      const auto* p = t->get_as<std::string>("pinion");
      const auto* g = t->get_as<std::string>("gear");
      if (p != nullptr && g != nullptr) name = p->get() + "-" + g->get();
    } else if (array_key == "bearing" || array_key == "load") {
      name = array_key + std::to_string(i);
    }
    if (name.empty()) continue;
    names.push_back(name);
    if (name == segment) {
      if (found) {
        ctx_.FailOverride(text, walked + "." + segment,
                          "ambiguous: several elements of '" + walked + "' are named '" + segment +
                              "'; select by index instead");
      }
      found = i;
    }
  }
  if (!found) {
    ctx_.FailOverride(text, walked + "." + segment,
                      "no element of '" + walked + "' is named '" + segment + "'" +
                          DidYouMean(segment, names) + "; names: " + JoinNames(names) +
                          "; or use a 0-based index");
  }
  return *found;
}

toml::node* Reader::StepInto(toml::node* current, const std::string& segment,
                             const std::string& walked, const std::string& parent_key,
                             const std::string& text, const std::string& marker) {
  const std::string here = walked.empty() ? segment : walked + "." + segment;
  if (toml::table* t = current->as_table()) {
    if (toml::node* child = t->get(segment)) return child;
    // Create the missing table (its source is the override, for error locations).
    toml::table created = toml::parse("v = {}", marker);
    t->insert_or_assign(segment, std::move(*created.get("v")->as_table()));
    return t->get(segment);
  }
  if (toml::array* a = current->as_array()) {
    return a->get(FindElement(*a, segment, walked, parent_key, text));
  }
  ctx_.FailOverride(
      text, here,
      "cannot descend into '" + walked + "': it is " + Describe(*current) + ", not a table");
}

void Reader::ApplyOverride(std::size_t index, const std::string& text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos) {
    ctx_.FailOverride(text, "", "malformed override: expected PATH=VALUE (no '=')");
  }
  const std::string path = Trim(std::string_view(text).substr(0, eq));
  const std::string value = Trim(std::string_view(text).substr(eq + 1));
  if (path.empty()) ctx_.FailOverride(text, "", "malformed override: empty path before '='");
  const std::vector<std::string> segments = Split(path, '.');
  for (const std::string& s : segments) {
    if (s.empty()) {
      ctx_.FailOverride(text, path, "malformed override: empty path segment (stray '.')");
    }
  }
  const std::string marker = ctx_.AddOverride(index, text);

  // The value as TOML; if it is not a single TOML value, as a bare string.
  toml::table parsed;
  bool ok = false;
  try {
    parsed = toml::parse("v = " + value, marker);
    ok = parsed.size() == 1 && parsed.contains("v");
  } catch (const toml::parse_error&) {
    ok = false;
  }
  if (!ok) parsed = toml::parse("v = " + QuoteToml(value), marker);
  toml::node& new_value = *parsed.get("v");

  toml::node* current = &root_;
  std::string walked;
  std::string parent_key;
  for (std::size_t i = 0; i + 1 < segments.size(); ++i) {
    current = StepInto(current, segments[i], walked, parent_key, text, marker);
    parent_key = segments[i];
    walked = walked.empty() ? segments[i] : walked + "." + segments[i];
  }
  const std::string& last = segments.back();
  if (toml::table* t = current->as_table()) {
    new_value.visit([&](auto& v) { t->insert_or_assign(last, std::move(v)); });
  } else if (toml::array* a = current->as_array()) {
    const std::size_t element = FindElement(*a, last, walked, parent_key, text);
    new_value.visit([&](auto& v) {
      a->replace(a->cbegin() + static_cast<std::ptrdiff_t>(element), std::move(v));
    });
  } else {
    ctx_.FailOverride(
        text, path,
        "cannot descend into '" + walked + "': it is " + Describe(*current) + ", not a table");
  }
}

// --- validation ------------------------------------------------------------------------------

const toml::array* Reader::ArrayOfTables(std::string_view key) const {
  const toml::node* n = root_.get(key);
  if (n == nullptr) return nullptr;
  const std::string k(key);
  const toml::array* a = n->as_array();
  if (a == nullptr) {
    ctx_.Fail(n, k, "must be an array of tables ([[" + k + "]]), got " + Describe(*n));
  }
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node* e = a->get(i);
    if (!e->is_table()) {
      ctx_.Fail(e, k + "[" + std::to_string(i) + "]",
                "must be a table ([[" + k + "]] or {...}), got " + Describe(*e));
    }
  }
  return a;
}

const GearDef& Reader::GearRef(const Fields& f, std::string_view key, const std::string& name,
                               const Scene& scene) const {
  for (const GearDef& g : scene.gears) {
    if (g.name == name) return g;
  }
  std::vector<std::string> names;
  for (const GearDef& g : scene.gears) names.push_back(g.name);
  f.Fail(key,
         "no gear named '" + name + "'" + DidYouMean(name, names) + "; gears: " + JoinNames(names));
}

// The element's `name` (or `default_name` if absent and not required), validated.
std::string Reader::ReadName(const Fields& indexed, bool required, std::string default_name) {
  std::optional<std::string> name = indexed.OptString("name");
  if (!name) {
    if (required) indexed.Missing("name", "a unique name (" + std::string(kNameRule) + ")");
    return default_name;
  }
  if (!IsValidName(*name)) {
    indexed.Fail("name", "'" + *name + "' is not a valid name (" + kNameRule + ")");
  }
  return *name;
}

// Key path prefix of an element: "kind.NAME" if its name is known and valid, else "kind[i]".
std::string ElementPrefix(const toml::table& t, const std::string& kind, std::size_t index,
                          const std::string& default_name) {
  std::string name = default_name;
  if (const toml::node* n = t.get("name")) {
    name = n->is_string() ? n->as_string()->get() : std::string();
  }
  return IsValidName(name) ? kind + "." + name : kind + "[" + std::to_string(index) + "]";
}

GearDef Reader::ReadGear(const toml::table& t, std::size_t index) {
  GearDef g;
  const Fields indexed(ctx_, t, "gear[" + std::to_string(index) + "]");
  const Fields f(ctx_, t, ElementPrefix(t, "gear", index, ""));
  f.CheckKnown({"name", "teeth", "normal_module", "normal_pressure_angle_deg", "helix_angle_deg",
                "hand", "face_width", "profile_shift", "addendum_coefficient",
                "dedendum_coefficient", "root_radius_coefficient", "tip_diameter", "internal",
                "web_thickness", "rim_thickness", "mass", "inertia", "transverse_inertia"});
  g.name = ReadName(indexed, true, "");

  GearBlank& b = g.blank;
  b.teeth = f.ReqPositiveInt("teeth", "number of teeth, a positive integer", kMaxTeeth);

  const Number module = f.ReqNumber("normal_module", "normal module in m");
  f.Metres("normal_module", module, kMaxModule);
  g.normal_module = module.value;

  if (auto alpha = f.OptNumber("normal_pressure_angle_deg")) {
    if (!(alpha->value > 0.0 && alpha->value < kMaxPressureAngleDeg)) {
      f.Fail("normal_pressure_angle_deg",
             "must be in (0, " + Num(kMaxPressureAngleDeg) + ") degrees, got " + Num(alpha->value));
    }
    g.normal_pressure_angle = DegToRad(alpha->value);
  } else {
    g.normal_pressure_angle = DegToRad(20.0);
  }

  double helix_deg = 0.0;
  if (auto beta = f.OptNumber("helix_angle_deg")) {
    if (beta->value < 0.0) {
      f.Fail("helix_angle_deg",
             "must be >= 0 (give the direction with hand = \"right\" or \"left\"), got " +
                 Num(beta->value));
    }
    if (beta->value > kMaxHelixAngleDeg) {
      f.Fail("helix_angle_deg",
             "must be at most " + Num(kMaxHelixAngleDeg) + " degrees, got " + Num(beta->value));
    }
    helix_deg = beta->value;
  }
  g.helix_angle = DegToRad(helix_deg);

  if (auto hand = f.OptString("hand")) {
    if (helix_deg == 0.0) {
      f.Fail("hand",
             "must not be given for a spur gear (helix_angle_deg is 0), got \"" + *hand + "\"");
    }
    if (*hand == "right") {
      g.hand = HelixHand::kRight;
    } else if (*hand == "left") {
      g.hand = HelixHand::kLeft;
    } else {
      const std::array<std::string_view, 2> hands = {"right", "left"};
      f.Fail("hand",
             "must be \"right\" or \"left\", got \"" + *hand + "\"" + DidYouMean(*hand, hands));
    }
  } else if (helix_deg != 0.0) {
    f.Missing("hand", "\"right\" or \"left\" for a helical gear (helix_angle_deg = " +
                          Num(helix_deg) + ")");
  }

  const Number face = f.ReqNumber("face_width", "face width in m");
  f.Metres("face_width", face, kMaxFaceWidth);
  b.face_width = face.value;

  if (auto x = f.OptNumber("profile_shift")) b.profile_shift = x->value;
  if (auto h = f.OptNumber("addendum_coefficient")) {
    f.Positive("addendum_coefficient", *h);
    b.addendum_coefficient = h->value;
  }
  if (auto h = f.OptNumber("dedendum_coefficient")) {
    f.Positive("dedendum_coefficient", *h);
    b.dedendum_coefficient = h->value;
  }
  if (auto rho = f.OptNumber("root_radius_coefficient")) {
    f.NonNegative("root_radius_coefficient", *rho);
    b.root_radius_coefficient = rho->value;
  }
  if (auto da = f.OptNumber("tip_diameter")) {
    f.Positive("tip_diameter", *da);
    b.tip_diameter = da->value;
  }
  if (auto internal = f.OptBool("internal")) {
    b.kind = *internal ? GearKind::kInternal : GearKind::kExternal;
  }
  if (auto web = f.OptNumber("web_thickness")) {
    f.Positive("web_thickness", *web);
    b.web_thickness = web->value;
  }
  if (auto rim = f.OptNumber("rim_thickness")) {
    f.Positive("rim_thickness", *rim);
    b.rim_thickness = rim->value;
  }

  const Number mass = f.ReqNumber("mass", "mass in kg, > 0");
  f.Positive("mass", mass);
  g.mass = mass.value;
  const Number inertia = f.ReqNumber("inertia", "polar moment of inertia in kg m², > 0");
  f.Positive("inertia", inertia);
  g.inertia = inertia.value;
  if (auto it = f.OptNumber("transverse_inertia")) {
    f.Positive("transverse_inertia", *it);
    // Triangle inequality of the principal moments of a rigid body: I_zz <= I_xx + I_yy.
    if (g.inertia > 2.0 * it->value * (1.0 + kEqualTol)) {
      f.Fail("transverse_inertia",
             "must be at least inertia/2 = " + Num(g.inertia / 2.0) +
                 " kg m² (no rigid body has a polar moment above the sum of the two transverse "
                 "ones), got " +
                 Num(it->value));
    }
    g.transverse_inertia = it->value;
  }
  return g;
}

MeshDef Reader::ReadMesh(const toml::table& t, std::size_t index, const Scene& scene) {
  MeshDef m;
  const Fields indexed(ctx_, t, "mesh[" + std::to_string(index) + "]");
  const auto* p_name = t.get_as<std::string>("pinion");
  const auto* g_name = t.get_as<std::string>("gear");
  const Fields named(
      ctx_, t,
      ElementPrefix(
          t, "mesh", index,
          p_name != nullptr && g_name != nullptr ? p_name->get() + "-" + g_name->get() : ""));
  named.CheckKnown({"name", "pinion", "gear", "center_distance"});
  m.pinion = named.ReqString("pinion", "name of the driving [[gear]]");
  m.gear = named.ReqString("gear", "name of the driven [[gear]]");
  m.name = ReadName(indexed, false, m.pinion + "-" + m.gear);
  const std::string prefix = "mesh." + m.name;
  const Fields f(ctx_, t, prefix);
  const GearDef& p = GearRef(f, "pinion", m.pinion, scene);
  const GearDef& g = GearRef(f, "gear", m.gear, scene);
  if (m.pinion == m.gear) f.Fail("gear", "a gear cannot mesh with itself ('" + m.gear + "')");
  if (p.blank.kind == GearKind::kInternal) {
    f.Fail("pinion", "'" + p.name +
                         "' is an internal gear; the pinion of a mesh must be external (make "
                         "the ring the mesh's gear)");
  }
  for (const MeshDef& other : scene.meshes) {
    if ((other.pinion == m.pinion && other.gear == m.gear) ||
        (other.pinion == m.gear && other.gear == m.pinion)) {
      ctx_.Fail(&t, prefix,
                "gears '" + m.pinion + "' and '" + m.gear + "' already mesh in mesh '" +
                    other.name + "'");
    }
  }

  const auto differs = [](double a, double b) {
    return std::abs(a - b) > kEqualTol * std::max(std::abs(a), std::abs(b));
  };
  const auto mismatch = [&](const std::string& what, const std::string& vp, const std::string& vg) {
    ctx_.Fail(&t, prefix,
              what + " differs: pinion '" + p.name + "' has " + vp + " but gear '" + g.name +
                  "' has " + vg + " (meshing gears need the same)");
  };
  if (differs(p.normal_module, g.normal_module)) {
    mismatch("normal_module", Num(p.normal_module) + " m", Num(g.normal_module) + " m");
  }
  if (differs(p.normal_pressure_angle, g.normal_pressure_angle)) {
    mismatch("normal_pressure_angle_deg", Deg(p.normal_pressure_angle),
             Deg(g.normal_pressure_angle));
  }
  if (differs(p.helix_angle, g.helix_angle)) {
    mismatch("helix_angle_deg", Deg(p.helix_angle), Deg(g.helix_angle));
  }
  const bool internal = g.blank.kind == GearKind::kInternal;
  if (p.hand != HelixHand::kNone) {
    const char* hand = p.hand == HelixHand::kRight ? "right" : "left";
    if (!internal && p.hand == g.hand) {
      ctx_.Fail(&t, prefix,
                std::string("external helical gears need opposite hands, but pinion '") + p.name +
                    "' and gear '" + g.name + "' are both " + hand + "-handed");
    }
    if (internal && p.hand != g.hand) {
      ctx_.Fail(&t, prefix,
                "an internal helical mesh needs equal hands, but pinion '" + p.name + "' is " +
                    hand + "-handed and ring '" + g.name + "' is not");
    }
  }

  GearPairSpec spec;
  spec.normal_module = p.normal_module;
  spec.normal_pressure_angle = p.normal_pressure_angle;
  spec.helix_angle = p.helix_angle;
  spec.pinion_hand = p.hand;
  spec.pinion = p.blank;
  spec.gear = g.blank;
  const toml::node* where = &t;
  if (auto a = f.OptNumber("center_distance")) {
    f.Positive("center_distance", *a);
    spec.center_distance = a->value;
  }
  try {
    m.geometry = CalcGearPairGeometry(spec);
  } catch (const InvalidInput& e) {
    const std::string reason = e.what();
    // A centre-distance problem is reported where the centre distance was given.
    if (reason.rfind("center_distance", 0) == 0 && f.Find("center_distance") != nullptr) {
      where = f.Find("center_distance");
    }
    ctx_.Fail(where, prefix, reason);
  }
  return m;
}

Matrix6 Reader::ReadMatrix6(const Fields& f, std::string_view key, const std::string& what) const {
  const toml::node* n = f.Find(key);
  const std::string forms =
      "an array of 6 numbers (diagonal) or of 6 rows of 6 numbers (full symmetric matrix)";
  if (n == nullptr) f.Missing(key, what + ": " + forms);
  const toml::array* a = n->as_array();
  if (a == nullptr) f.Fail(key, "must be " + forms + ", got " + Describe(*n));
  const std::string k = f.Key(key);
  const auto entry = [&](const toml::node& e, const std::string& pos) {
    double v = 0.0;
    if (const auto* i = e.as_integer()) {
      v = static_cast<double>(i->get());
    } else if (const auto* fl = e.as_floating_point()) {
      v = fl->get();
    } else {
      ctx_.Fail(&e, k, "entry " + pos + " must be a number, got " + Describe(e));
    }
    if (!std::isfinite(v)) ctx_.Fail(&e, k, "entry " + pos + " must be finite, got " + Num(v));
    return v;
  };
  Matrix6 m = Matrix6::Zero();
  const bool rows = a->size() > 0 && a->get(0)->is_array();
  if (a->size() != 6) {
    f.Fail(key, "must have 6 entries (diagonal) or 6 rows of 6 (full matrix), got " +
                    std::to_string(a->size()) + (rows ? " rows" : " entries"));
  }
  if (!rows) {
    for (int i = 0; i < 6; ++i) {
      const toml::node& e = *a->get(static_cast<std::size_t>(i));
      const std::string pos = std::to_string(i) + " (" + kDofNames[i] + ")";
      if (e.is_array()) {
        ctx_.Fail(&e, k, "mixes numbers and rows: entry " + pos + " is an array");
      }
      m(i, i) = entry(e, pos);
      if (m(i, i) < 0.0) {
        ctx_.Fail(&e, k, "diagonal entry " + pos + " must be >= 0, got " + Num(m(i, i)));
      }
    }
    return m;
  }
  for (int i = 0; i < 6; ++i) {
    const toml::node& r = *a->get(static_cast<std::size_t>(i));
    const toml::array* row = r.as_array();
    if (row == nullptr) {
      ctx_.Fail(&r, k, "mixes numbers and rows: row " + std::to_string(i) + " is " + Describe(r));
    }
    if (row->size() != 6) {
      ctx_.Fail(&r, k,
                "row " + std::to_string(i) + " (" + kDofNames[i] + ") must have 6 entries, got " +
                    std::to_string(row->size()));
    }
    for (int j = 0; j < 6; ++j) {
      m(i, j) = entry(*row->get(static_cast<std::size_t>(j)),
                      "[" + std::to_string(i) + "][" + std::to_string(j) + "]");
    }
  }
  for (int i = 0; i < 6; ++i) {
    for (int j = i + 1; j < 6; ++j) {
      if (std::abs(m(i, j) - m(j, i)) >
          kSymmetryTol * std::max(std::abs(m(i, j)), std::abs(m(j, i)))) {
        ctx_.Fail(a->get(static_cast<std::size_t>(j)), k,
                  "not symmetric: [" + std::to_string(i) + "][" + std::to_string(j) + "] (" +
                      kDofNames[i] + "," + kDofNames[j] + ") = " + Num(m(i, j)) + " but [" +
                      std::to_string(j) + "][" + std::to_string(i) + "] = " + Num(m(j, i)));
      }
    }
  }
  m = (0.5 * (m + m.transpose())).eval();
  // Positive semi-definite. The entries mix units (N/m, N/rad, N m/rad), so test the diagonally
  // scaled matrix S K S with S = diag(1/sqrt(K_ii)), whose eigenvalues are unit-free.
  for (int i = 0; i < 6; ++i) {
    if (m(i, i) < 0.0) {
      ctx_.Fail(a->get(static_cast<std::size_t>(i)), k,
                "not positive semi-definite: diagonal entry [" + std::to_string(i) + "][" +
                    std::to_string(i) + "] (" + kDofNames[i] + ") = " + Num(m(i, i)) + " < 0");
    }
    if (m(i, i) == 0.0) {
      for (int j = 0; j < 6; ++j) {
        if (m(i, j) != 0.0) {
          ctx_.Fail(a->get(static_cast<std::size_t>(i)), k,
                    "not positive semi-definite: diagonal entry [" + std::to_string(i) + "][" +
                        std::to_string(i) + "] (" + kDofNames[i] + ") is 0 but [" +
                        std::to_string(i) + "][" + std::to_string(j) + "] = " + Num(m(i, j)));
        }
      }
    }
  }
  Vector6 s;
  for (int i = 0; i < 6; ++i) s(i) = m(i, i) > 0.0 ? 1.0 / std::sqrt(m(i, i)) : 1.0;
  const Matrix6 scaled = s.asDiagonal() * m * s.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Matrix6> eig(scaled, Eigen::EigenvaluesOnly);
  const double lowest = eig.eigenvalues()(0);
  if (lowest < -kPsdTol) {
    f.Fail(key, "not positive semi-definite: the diagonally scaled matrix has eigenvalue " +
                    Num(lowest) + " < 0 (off-diagonal couplings too large for the diagonal)");
  }
  return m;
}

BearingDef Reader::ReadBearing(const toml::table& t, std::size_t index, const Scene& scene) {
  BearingDef bd;
  const std::string default_name = "bearing" + std::to_string(index);
  {
    const Fields f(ctx_, t, ElementPrefix(t, "bearing", index, default_name));
    f.CheckKnown({"name", "body", "other", "stiffness", "damping"});
  }
  bd.name =
      ReadName(Fields(ctx_, t, "bearing[" + std::to_string(index) + "]"), false, default_name);
  const Fields f(ctx_, t, "bearing." + bd.name);
  bd.body = f.ReqString("body", "name of the supported [[gear]]");
  (void)GearRef(f, "body", bd.body, scene);
  if (auto other = f.OptString("other")) {
    bd.other = *other;
    (void)GearRef(f, "other", bd.other, scene);
    if (bd.other == bd.body) {
      f.Fail("other", "must differ from body ('" + bd.body + "'); omit it for a ground bearing");
    }
  }
  bd.stiffness = ReadMatrix6(f, "stiffness", "stiffness in N/m, N/rad, N m/rad");
  if (f.Find("damping") != nullptr) {
    bd.damping = ReadMatrix6(f, "damping", "damping in N s/m, N s/rad, N m s/rad");
  }
  return bd;
}

TorqueLoadDef Reader::ReadLoad(const toml::table& t, std::size_t index, const Scene& scene) {
  TorqueLoadDef ld;
  const std::string default_name = "load" + std::to_string(index);
  {
    const Fields f(ctx_, t, ElementPrefix(t, "load", index, default_name));
    f.CheckKnown({"name", "body", "torque"});
  }
  ld.name = ReadName(Fields(ctx_, t, "load[" + std::to_string(index) + "]"), false, default_name);
  const Fields f(ctx_, t, "load." + ld.name);
  ld.body = f.ReqString("body", "name of the loaded [[gear]]");
  (void)GearRef(f, "body", ld.body, scene);
  ld.torque = f.ReqNumber("torque", "torque in N m about the common +z axis").value;
  return ld;
}

OperatingPointDef Reader::ReadOperatingPoint(const Scene& scene) {
  const toml::node* n = root_.get("operating_point");
  if (n == nullptr) {
    ctx_.Fail(nullptr, "operating_point",
              "missing (required: an [operating_point] table with speed_rpm and torque)");
  }
  const toml::table* t = n->as_table();
  if (t == nullptr) {
    ctx_.Fail(n, "operating_point", "must be a table ([operating_point]), got " + Describe(*n));
  }
  const Fields f(ctx_, *t, "operating_point");
  f.CheckKnown({"body", "speed_rpm", "torque"});
  OperatingPointDef op;
  if (auto body = f.OptString("body")) {
    op.body = *body;
    (void)GearRef(f, "body", op.body, scene);
  } else {
    op.body = scene.meshes.front().pinion;
  }
  const Number speed = f.ReqNumber("speed_rpm", "speed of the reference gear in rpm, >= 0");
  f.NonNegative("speed_rpm", speed);
  op.speed = RpmToRadPerSec(speed.value);
  op.torque = f.ReqNumber("torque", "mean torque on the reference gear in N m").value;
  return op;
}

Scene Reader::Validate() {
  Scene scene;
  scene.source = ctx_.source();
  const Fields top(ctx_, root_, "");
  top.CheckKnown({"title", "gear", "mesh", "bearing", "load", "operating_point"});
  if (auto title = top.OptString("title")) scene.title = *title;

  // Gears.
  const toml::array* gears = ArrayOfTables("gear");
  if (gears == nullptr || gears->empty()) {
    ctx_.Fail(nullptr, "gear", "the scene has no gear (at least one [[gear]] is required)");
  }
  std::map<std::string, const toml::table*> gear_tables;
  for (std::size_t i = 0; i < gears->size(); ++i) {
    const toml::table& t = *gears->get(i)->as_table();
    GearDef g = ReadGear(t, i);
    if (const auto it = gear_tables.find(g.name); it != gear_tables.end()) {
      const int first = ctx_.Line(it->second);
      ctx_.Fail(t.get("name"), "gear[" + std::to_string(i) + "].name",
                "duplicate gear name '" + g.name + "'" +
                    (first > 0 ? " (first defined at line " + std::to_string(first) + ")" : ""));
    }
    gear_tables.emplace(g.name, &t);
    scene.gears.push_back(std::move(g));
  }

  // Meshes.
  const toml::array* meshes = ArrayOfTables("mesh");
  if (meshes == nullptr || meshes->empty()) {
    ctx_.Fail(nullptr, "mesh", "the scene has no mesh (at least one [[mesh]] is required)");
  }
  std::map<std::string, const toml::table*> mesh_tables;
  for (std::size_t i = 0; i < meshes->size(); ++i) {
    const toml::table& t = *meshes->get(i)->as_table();
    MeshDef m = ReadMesh(t, i, scene);
    if (const auto it = mesh_tables.find(m.name); it != mesh_tables.end()) {
      const int first = ctx_.Line(it->second);
      ctx_.Fail(&t, "mesh[" + std::to_string(i) + "].name",
                "duplicate mesh name '" + m.name + "'" +
                    (first > 0 ? " (first defined at line " + std::to_string(first) + ")" : ""));
    }
    mesh_tables.emplace(m.name, &t);
    scene.meshes.push_back(std::move(m));
  }

  // Bearings.
  std::map<std::string, const toml::table*> bearing_tables;
  if (const toml::array* bearings = ArrayOfTables("bearing")) {
    for (std::size_t i = 0; i < bearings->size(); ++i) {
      const toml::table& t = *bearings->get(i)->as_table();
      BearingDef bd = ReadBearing(t, i, scene);
      if (const auto it = bearing_tables.find(bd.name); it != bearing_tables.end()) {
        const int first = ctx_.Line(it->second);
        ctx_.Fail(&t, "bearing[" + std::to_string(i) + "].name",
                  "duplicate bearing name '" + bd.name + "'" +
                      (first > 0 ? " (first defined at line " + std::to_string(first) + ")" : ""));
      }
      bearing_tables.emplace(bd.name, &t);
      scene.bearings.push_back(std::move(bd));
    }
  }

  // Loads.
  std::map<std::string, const toml::table*> load_tables;
  if (const toml::array* loads = ArrayOfTables("load")) {
    for (std::size_t i = 0; i < loads->size(); ++i) {
      const toml::table& t = *loads->get(i)->as_table();
      TorqueLoadDef ld = ReadLoad(t, i, scene);
      if (const auto it = load_tables.find(ld.name); it != load_tables.end()) {
        const int first = ctx_.Line(it->second);
        ctx_.Fail(&t, "load[" + std::to_string(i) + "].name",
                  "duplicate load name '" + ld.name + "'" +
                      (first > 0 ? " (first defined at line " + std::to_string(first) + ")" : ""));
      }
      load_tables.emplace(ld.name, &t);
      scene.loads.push_back(std::move(ld));
    }
  }

  scene.operating_point = ReadOperatingPoint(scene);

  // Kinematics: loops of meshes (and torsionally stiff bearings) must close.
  const internal::SpeedRatios ratios = internal::CalcSpeedRatios(scene, scene.operating_point.body);
  if (ratios.conflict_mesh || ratios.conflict_bearing) {
    const bool is_mesh = ratios.conflict_mesh.has_value();
    const std::string name = is_mesh ? scene.meshes[*ratios.conflict_mesh].name
                                     : scene.bearings[*ratios.conflict_bearing].name;
    const toml::table* t = is_mesh ? mesh_tables.at(name) : bearing_tables.at(name);
    ctx_.Fail(t, (is_mesh ? "mesh." : "bearing.") + name,
              "kinematically locked loop: through the other elements gear '" +
                  ratios.conflict_gear + "' turns at " + Num(ratios.ratio_known) +
                  " x the reference speed, but this " + (is_mesh ? "mesh" : "torsional coupling") +
                  " requires " + Num(ratios.ratio_implied) + " x");
  }
  return scene;
}

}  // namespace

SceneError::SceneError(std::string source, int line, std::string key, std::string reason,
                       std::string override_spec)
    : InvalidInput(FormatWhat(source, line, key, reason, override_spec)),
      source_(std::move(source)),
      line_(line),
      key_(std::move(key)),
      reason_(std::move(reason)),
      override_spec_(std::move(override_spec)) {}

Scene ParseScene(std::string_view toml_text, const std::string& source_name,
                 const std::vector<std::string>& overrides) {
  Reader reader(source_name);
  reader.Parse(toml_text);
  for (std::size_t i = 0; i < overrides.size(); ++i) reader.ApplyOverride(i, overrides[i]);
  return reader.Validate();
}

Scene LoadScene(const std::string& path_or_builtin, const std::vector<std::string>& overrides) {
  constexpr std::string_view kBuiltin = "builtin:";
  if (path_or_builtin.rfind(kBuiltin, 0) == 0) {
    const std::string name = path_or_builtin.substr(kBuiltin.size());
    const std::optional<std::string_view> text = BuiltinSceneText(name);
    if (!text) {
      const std::vector<std::string> names = BuiltinSceneNames();
      throw SceneError(path_or_builtin, 0, "",
                       "no built-in scene named '" + name + "'" + DidYouMean(name, names) +
                           "; built-in scenes: " + JoinNames(names));
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
