/// @file
/// @brief Typed access to the keys of one TOML table of a scene, failing with
/// `FILE:LINE: KEY: REASON` (internal to the scene reader).
///
/// Getters come in pairs: OptX returns std::nullopt for an absent key, ReqX fails with
/// "missing (required: WHAT)". Both fail on a present value of the wrong type, naming what was
/// found (Describe). Numbers are integers or floats and must be finite.
#pragma once

#include <toml++/toml.h>

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "scene/error_context.hpp"

namespace geardyn::internal {

/// @brief Shortest round-trip representation of `v` ("0.003", "1e+10", "inf", "nan").
std::string FormatNumber(double v);

/// @brief What a node holds, for "got ..." texts: `string "abc"`, `-5 (an integer)`,
/// `0.5 (a float)`, `boolean true`, `an array`, `a table`, ...
std::string Describe(const toml::node& n);

/// @brief The value of `n` as a finite double (an integer or a float).
/// @throws SceneError at `n` under `key`: "<subject>must be a number, got ..." or
///   "<subject>must be finite, got ..." (`subject` is empty or ends in a space: "entry 3 ").
double ReadFiniteNumber(const ErrorContext& ctx, const toml::node& n, const std::string& key,
                        const std::string& subject = {});

/// A number read from the tree, with the node it came from (for error locations).
struct Number {
  double value = 0.0;
  const toml::node* node = nullptr;
};

/// @brief Typed access to the keys of one table, with `prefix` the key path of the table
/// ("gear.wheel", "gear[1]", "operating_point"; empty for the top level).
class Fields {
 public:
  Fields(const ErrorContext& ctx, const toml::table& table, std::string prefix)
      : ctx_(ctx), table_(table), prefix_(std::move(prefix)) {}

  /// The full key path of `key` in this table ("gear.wheel.teeth").
  std::string Key(std::string_view key) const {
    return prefix_.empty() ? std::string(key) : prefix_ + "." + std::string(key);
  }
  const toml::node* Find(std::string_view key) const { return table_.get(key); }
  const toml::table& table() const { return table_; }
  const ErrorContext& context() const { return ctx_; }
  /// The key path of the table itself ("gear.wheel").
  const std::string& prefix() const { return prefix_; }

  /// Fails at `key`'s value (or, if absent, at the file) under its full key path.
  [[noreturn]] void Fail(std::string_view key, const std::string& reason) const {
    ctx_.Fail(Find(key), Key(key), reason);
  }

  /// Fails at the table: "missing (required: WHAT)".
  [[noreturn]] void Missing(std::string_view key, const std::string& what) const;

  /// @brief Rejects any key not in `allowed`: the first such key in file order (then overridden
  /// keys), with a "did you mean" hint or the list of allowed keys.
  void CheckKnown(std::initializer_list<std::string_view> allowed) const;

  std::optional<Number> OptNumber(std::string_view key) const;
  Number ReqNumber(std::string_view key, const std::string& what) const;
  /// A number that must be > 0 if given.
  std::optional<double> OptPositive(std::string_view key) const;
  /// A required number, > 0.
  double ReqPositive(std::string_view key, const std::string& what) const;
  /// Positive integer (tooth counts) in [1, max].
  int ReqPositiveInt(std::string_view key, const std::string& what, std::int64_t max) const;
  std::optional<std::string> OptString(std::string_view key) const;
  std::string ReqString(std::string_view key, const std::string& what) const;
  std::optional<bool> OptBool(std::string_view key) const;
  /// An integer in [min, max] if given ("must be an integer", "must be >= MIN", ...).
  std::optional<int> OptInt(std::string_view key, int min, int max) const;
  /// A sub-table ([prefix.key] or an inline table) if given; fails on any other value.
  const toml::table* OptTable(std::string_view key) const;
  /// An array of finite numbers (possibly empty) if given; entry errors name the entry
  /// ("entry 3 must be a number, got ...") and are located at it.
  std::optional<std::vector<Number>> OptNumberArray(std::string_view key) const;

  // Bound checks on a number read from this table.
  void Positive(std::string_view key, const Number& n) const;
  void NonNegative(std::string_view key, const Number& n) const;
  /// A length in metres, > 0 and at most `max` (catches millimetres given as metres).
  void Metres(std::string_view key, const Number& n, double max) const;

 private:
  const ErrorContext& ctx_;
  const toml::table& table_;
  std::string prefix_;
};

}  // namespace geardyn::internal
