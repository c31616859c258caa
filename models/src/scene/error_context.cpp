// Locating scene errors (file line or --set override) and formatting SceneError's message.
#include "scene/error_context.hpp"

#include "geardyn/models/scene/scene_reader.hpp"

namespace geardyn {
namespace {

std::string FormatWhat(const std::string& source, int line, const std::string& key,
                       const std::string& reason, const std::string& override_spec) {
  // Appended piece by piece: `":" + std::to_string(line)` trips GCC 12's -Wrestrict false
  // positive in Release builds.
  std::string out = source;
  if (line > 0) {
    out.append(":").append(std::to_string(line));
  } else if (!override_spec.empty()) {
    out.append(": --set ").append(override_spec);
  }
  out.append(": ");
  if (!key.empty()) out.append(key).append(": ");
  return out.append(reason);
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

namespace internal {

std::string ErrorContext::AddOverride(std::size_t index, const std::string& text) {
  std::string marker = "--set#" + std::to_string(index);
  overrides_[marker] = text;
  return marker;
}

std::pair<int, std::string> ErrorContext::Where(const toml::node* node) const {
  if (node == nullptr) return {0, {}};
  const toml::source_region& src = node->source();
  if (src.path) {
    const auto it = overrides_.find(*src.path);
    if (it != overrides_.end()) return {0, it->second};
  }
  return {static_cast<int>(src.begin.line), {}};
}

void ErrorContext::Fail(const toml::node* where, const std::string& key,
                        const std::string& reason) const {
  auto [line, override_spec] = Where(where);
  throw SceneError(source_, line, key, reason, std::move(override_spec));
}

void ErrorContext::FailOverride(const std::string& override_spec, const std::string& key,
                                const std::string& reason) const {
  throw SceneError(source_, 0, key, reason, override_spec);
}

}  // namespace internal
}  // namespace geardyn
