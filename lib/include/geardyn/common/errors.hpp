/// @file
/// @brief The two exception types of geardyn: bad user input and broken internal invariants.
///
/// Numerical outcomes (no convergence, ill-conditioning) are never exceptions: they are reported
/// in an analysis result's Summary (see summary.hpp).
#pragma once

#include <stdexcept>
#include <string>

namespace geardyn {

/// @brief Bad user input: the message names the argument or field, its value and the bound.
class InvalidInput : public std::invalid_argument {
 public:
  explicit InvalidInput(const std::string& what) : std::invalid_argument(what) {}
};

/// @brief A broken internal invariant (a bug in geardyn), thrown so that a sweep survives it.
class InternalError : public std::logic_error {
 public:
  explicit InternalError(const std::string& what) : std::logic_error(what) {}
};

}  // namespace geardyn
