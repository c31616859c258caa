/// @file
/// @brief The three assertion tiers: user input (throws InvalidInput), internal invariants
/// (always on, throws InternalError) and debug-only checks for hot loops.
#pragma once

#include <sstream>
#include <string>

#include "geardyn/common/errors.hpp"

/// Throws geardyn::InvalidInput with the streamed message `msg` unless `cond` holds.
/// Usage: GEARDYN_THROW_UNLESS(teeth > 0, "teeth: must be positive, got " << teeth);
#define GEARDYN_THROW_UNLESS(cond, msg)                  \
  do {                                                   \
    if (!(cond)) {                                       \
      std::ostringstream geardyn_oss_;                   \
      geardyn_oss_ << msg;                               \
      throw ::geardyn::InvalidInput(geardyn_oss_.str()); \
    }                                                    \
  } while (false)

/// Throws geardyn::InvalidInput unless `actual == expected`; `what` names the argument.
#define GEARDYN_CHECK_SIZE(actual, expected, what)                                     \
  GEARDYN_THROW_UNLESS((actual) == (expected), what << ": size " << (actual)           \
                                                    << " does not match the expected " \
                                                    << (expected))

/// Internal invariant, always checked; throws geardyn::InternalError naming file and line.
#define GEARDYN_DEMAND(cond)                                                                       \
  do {                                                                                             \
    if (!(cond)) {                                                                                 \
      throw ::geardyn::InternalError(std::string("internal invariant failed: ") + #cond + " at " + \
                                     __FILE__ + ":" + std::to_string(__LINE__));                   \
    }                                                                                              \
  } while (false)

#ifdef NDEBUG
#define GEARDYN_ASSERT(cond) ((void)0)
#else
/// Debug-only invariant for hot loops.
#define GEARDYN_ASSERT(cond) GEARDYN_DEMAND(cond)
#endif
