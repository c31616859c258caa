// Typed, located access to the keys of a scene's TOML tables.
#include "scene/toml_fields.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>

#include "scene/suggestions.hpp"

namespace geardyn::internal {

std::string FormatNumber(double v) {
  std::array<char, 64> buf{};
  const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return std::string(buf.data(), res.ptr);
}

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
      return FormatNumber(n.as_floating_point()->get()) + " (a float)";
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

double ReadFiniteNumber(const ErrorContext& ctx, const toml::node& n, const std::string& key,
                        const std::string& subject) {
  double v = 0.0;
  if (const auto* i = n.as_integer()) {
    v = static_cast<double>(i->get());
  } else if (const auto* f = n.as_floating_point()) {
    v = f->get();
  } else {
    ctx.Fail(&n, key, subject + "must be a number, got " + Describe(n));
  }
  if (!std::isfinite(v)) ctx.Fail(&n, key, subject + "must be finite, got " + FormatNumber(v));
  return v;
}

void Fields::Missing(std::string_view key, const std::string& what) const {
  ctx_.Fail(&table_, Key(key), "missing (required: " + what + ")");
}

void Fields::CheckKnown(std::initializer_list<std::string_view> allowed) const {
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

std::optional<Number> Fields::OptNumber(std::string_view key) const {
  const toml::node* n = Find(key);
  if (n == nullptr) return std::nullopt;
  return Number{ReadFiniteNumber(ctx_, *n, Key(key)), n};
}

Number Fields::ReqNumber(std::string_view key, const std::string& what) const {
  std::optional<Number> n = OptNumber(key);
  if (!n) Missing(key, what);
  return *n;
}

std::optional<double> Fields::OptPositive(std::string_view key) const {
  const std::optional<Number> n = OptNumber(key);
  if (!n) return std::nullopt;
  Positive(key, *n);
  return n->value;
}

double Fields::ReqPositive(std::string_view key, const std::string& what) const {
  const Number n = ReqNumber(key, what);
  Positive(key, n);
  return n.value;
}

int Fields::ReqPositiveInt(std::string_view key, const std::string& what, std::int64_t max) const {
  const toml::node* n = Find(key);
  if (n == nullptr) Missing(key, what);
  const auto* i = n->as_integer();
  if (i == nullptr) Fail(key, "must be a positive integer, got " + Describe(*n));
  const std::int64_t v = i->get();
  if (v <= 0) Fail(key, "must be a positive integer, got " + std::to_string(v));
  if (v > max) Fail(key, "must be at most " + std::to_string(max) + ", got " + std::to_string(v));
  return static_cast<int>(v);
}

std::optional<std::string> Fields::OptString(std::string_view key) const {
  const toml::node* n = Find(key);
  if (n == nullptr) return std::nullopt;
  const auto* s = n->as_string();
  if (s == nullptr) Fail(key, "must be a string, got " + Describe(*n));
  return s->get();
}

std::string Fields::ReqString(std::string_view key, const std::string& what) const {
  std::optional<std::string> s = OptString(key);
  if (!s) Missing(key, what);
  return *s;
}

std::optional<bool> Fields::OptBool(std::string_view key) const {
  const toml::node* n = Find(key);
  if (n == nullptr) return std::nullopt;
  const auto* b = n->as_boolean();
  if (b == nullptr) Fail(key, "must be a boolean (true or false), got " + Describe(*n));
  return b->get();
}

std::optional<int> Fields::OptInt(std::string_view key, int min, int max) const {
  const toml::node* n = Find(key);
  if (n == nullptr) return std::nullopt;
  const auto* i = n->as_integer();
  if (i == nullptr) Fail(key, "must be an integer, got " + Describe(*n));
  const std::int64_t v = i->get();
  if (v < min) Fail(key, "must be >= " + std::to_string(min) + ", got " + std::to_string(v));
  if (v > max) Fail(key, "must be at most " + std::to_string(max) + ", got " + std::to_string(v));
  return static_cast<int>(v);
}

const toml::table* Fields::OptTable(std::string_view key) const {
  const toml::node* n = Find(key);
  if (n == nullptr) return nullptr;
  const toml::table* t = n->as_table();
  if (t == nullptr) Fail(key, "must be a table, got " + Describe(*n));
  return t;
}

std::optional<std::vector<Number>> Fields::OptNumberArray(std::string_view key) const {
  const toml::node* n = Find(key);
  if (n == nullptr) return std::nullopt;
  const toml::array* a = n->as_array();
  if (a == nullptr) Fail(key, "must be an array of numbers, got " + Describe(*n));
  std::vector<Number> out;
  out.reserve(a->size());
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node* e = a->get(i);
    out.push_back({ReadFiniteNumber(ctx_, *e, Key(key), "entry " + std::to_string(i) + " "), e});
  }
  return out;
}

void Fields::Positive(std::string_view key, const Number& n) const {
  if (!(n.value > 0.0)) Fail(key, "must be > 0, got " + FormatNumber(n.value));
}

void Fields::NonNegative(std::string_view key, const Number& n) const {
  if (!(n.value >= 0.0)) Fail(key, "must be >= 0, got " + FormatNumber(n.value));
}

void Fields::Metres(std::string_view key, const Number& n, double max) const {
  Positive(key, n);
  if (n.value > max) {
    Fail(key, "must be at most " + FormatNumber(max) +
                  " m (lengths are in metres: 3 mm is 0.003), got " + FormatNumber(n.value));
  }
}

}  // namespace geardyn::internal
