// `--set PATH=VALUE` overrides: parsing the text and splicing the value into the TOML tree.
#include "scene/overrides.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "scene/element_names.hpp"
#include "scene/suggestions.hpp"
#include "scene/toml_fields.hpp"

namespace geardyn::internal {
namespace {

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

// One override being applied: its text, its source marker and the context to fail in.
class OverrideWalker {
 public:
  OverrideWalker(const ErrorContext& ctx, std::string text, std::string marker)
      : ctx_(ctx), text_(std::move(text)), marker_(std::move(marker)) {}

  // The element of `array` (reached by the path `walked`, whose last segment is `array_key`)
  // that `segment` selects: a 0-based index, or an element name (given or default).
  std::size_t FindElement(const toml::array& array, const std::string& segment,
                          const std::string& walked, const std::string& array_key) const;

  // The child `segment` of `current` (a table: created if missing; an array: FindElement).
  toml::node* StepInto(toml::node* current, const std::string& segment, const std::string& walked,
                       const std::string& parent_key) const;

  [[noreturn]] void CannotDescend(const std::string& key, const std::string& walked,
                                  const toml::node& current) const {
    ctx_.FailOverride(
        text_, key,
        "cannot descend into '" + walked + "': it is " + Describe(current) + ", not a table");
  }

 private:
  const ErrorContext& ctx_;
  std::string text_;
  std::string marker_;
};

std::size_t OverrideWalker::FindElement(const toml::array& array, const std::string& segment,
                                        const std::string& walked,
                                        const std::string& array_key) const {
  if (IsIndex(segment)) {
    const std::size_t index = std::stoul(segment);
    if (index >= array.size()) {
      ctx_.FailOverride(text_, walked + "." + segment,
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
    const auto* given = t->get_as<std::string>("name");
    const std::string name = given != nullptr ? given->get() : DefaultElementName(array_key, *t, i);
    if (name.empty()) continue;
    names.push_back(name);
    if (name == segment) {
      if (found) {
        ctx_.FailOverride(text_, walked + "." + segment,
                          "ambiguous: several elements of '" + walked + "' are named '" + segment +
                              "'; select by index instead");
      }
      found = i;
    }
  }
  if (!found) {
    ctx_.FailOverride(text_, walked + "." + segment,
                      "no element of '" + walked + "' is named '" + segment + "'" +
                          DidYouMean(segment, names) + "; names: " + JoinNames(names) +
                          "; or use a 0-based index");
  }
  return *found;
}

toml::node* OverrideWalker::StepInto(toml::node* current, const std::string& segment,
                                     const std::string& walked,
                                     const std::string& parent_key) const {
  if (toml::table* t = current->as_table()) {
    if (toml::node* child = t->get(segment)) return child;
    // Create the missing table (its source is the override, for error locations).
    toml::table created = toml::parse("v = {}", marker_);
    t->insert_or_assign(segment, std::move(*created.get("v")->as_table()));
    return t->get(segment);
  }
  if (toml::array* a = current->as_array()) {
    return a->get(FindElement(*a, segment, walked, parent_key));
  }
  CannotDescend(walked.empty() ? segment : walked + "." + segment, walked, *current);
}

}  // namespace

void ApplyOverride(ErrorContext& ctx, toml::table& root, std::size_t index,
                   const std::string& text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos) {
    ctx.FailOverride(text, "", "malformed override: expected PATH=VALUE (no '=')");
  }
  const std::string path = Trim(std::string_view(text).substr(0, eq));
  const std::string value = Trim(std::string_view(text).substr(eq + 1));
  if (path.empty()) ctx.FailOverride(text, "", "malformed override: empty path before '='");
  const std::vector<std::string> segments = Split(path, '.');
  for (const std::string& s : segments) {
    if (s.empty()) {
      ctx.FailOverride(text, path, "malformed override: empty path segment (stray '.')");
    }
  }
  const std::string marker = ctx.AddOverride(index, text);
  const OverrideWalker walker(ctx, text, marker);

  // The value as TOML; if it is not a single TOML value, as a bare string.
  toml::table parsed;
  bool ok = false;
  try {
    parsed = toml::parse("v = " + value, marker);
    ok = parsed.size() == 1 && parsed.contains("v");
  } catch (const toml::parse_error&) {
    ok = false;
  }
  if (!ok) {
    // Even quoted, a value that is not valid UTF-8 is no TOML string: toml++'s parse_error
    // escaped the reader here (found with the fuzz entry, tests/fuzz/regressions/scene_reader/).
    try {
      parsed = toml::parse("v = " + QuoteToml(value), marker);
    } catch (const toml::parse_error& e) {
      ctx.FailOverride(
          text, path,
          "the value is neither a TOML value nor a valid string: " + std::string(e.description()));
    }
  }
  toml::node& new_value = *parsed.get("v");

  toml::node* current = &root;
  std::string walked;
  std::string parent_key;
  for (std::size_t i = 0; i + 1 < segments.size(); ++i) {
    current = walker.StepInto(current, segments[i], walked, parent_key);
    parent_key = segments[i];
    walked = walked.empty() ? segments[i] : walked + "." + segments[i];
  }
  const std::string& last = segments.back();
  if (toml::table* t = current->as_table()) {
    new_value.visit([&](auto& v) { t->insert_or_assign(last, std::move(v)); });
  } else if (toml::array* a = current->as_array()) {
    const std::size_t element = walker.FindElement(*a, last, walked, parent_key);
    new_value.visit([&](auto& v) {
      a->replace(a->cbegin() + static_cast<std::ptrdiff_t>(element), std::move(v));
    });
  } else {
    walker.CannotDescend(path, walked, *current);
  }
}

}  // namespace geardyn::internal
