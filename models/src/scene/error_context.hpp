/// @file
/// @brief Where a node of a scene's TOML tree came from, and throwing a SceneError there
/// (internal to the scene reader).
///
/// Every toml++ node carries source().begin.line and source().path. The scene text is parsed with
/// path = the source name; each override value is parsed from its own little TOML document whose
/// path is a private marker ("--set#<i>"). Moving a node keeps its source, so after the overrides
/// are spliced into the tree, a node's path tells whether it came from the file (report
/// FILE:LINE) or from an override (report FILE: --set TEXT).
#pragma once

#include <toml++/toml.h>

#include <cstddef>
#include <map>
#include <string>
#include <utility>

namespace geardyn::internal {

/// @brief The source name of a scene and the override markers registered on its tree.
class ErrorContext {
 public:
  explicit ErrorContext(std::string source) : source_(std::move(source)) {}

  /// The file path or "builtin:NAME" errors name.
  const std::string& source() const { return source_; }

  /// @brief Registers the source-path marker of override number `index` (text `text`).
  /// @return the marker to parse the override's value with
  std::string AddOverride(std::size_t index, const std::string& text);

  /// @brief Line of `node` in the file (0 if unknown or from an override) and the text of the
  /// override it came from (empty if from the file).
  std::pair<int, std::string> Where(const toml::node* node) const;

  /// The line of `node` in the file, 0 if unknown or from an override.
  int Line(const toml::node* node) const { return Where(node).first; }

  /// @brief Throws SceneError located at `where` (nullptr: the whole file).
  [[noreturn]] void Fail(const toml::node* where, const std::string& key,
                         const std::string& reason) const;

  /// @brief Throws SceneError located at the override `override_spec` itself.
  [[noreturn]] void FailOverride(const std::string& override_spec, const std::string& key,
                                 const std::string& reason) const;

 private:
  std::string source_;
  std::map<std::string, std::string> overrides_;  // source-path marker → override text
};

}  // namespace geardyn::internal
