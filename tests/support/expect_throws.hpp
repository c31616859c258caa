/// @file
/// @brief EXPECT_THROWS_MESSAGE(expr, ExceptionType, regex): the exception type and its message.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#define EXPECT_THROWS_MESSAGE(expr, exception_type, regex)                              \
  EXPECT_THROW(                                                                         \
      {                                                                                 \
        try {                                                                           \
          (void)(expr);                                                                 \
        } catch (const exception_type& geardyn_e_) {                                    \
          EXPECT_THAT(std::string(geardyn_e_.what()), ::testing::ContainsRegex(regex)); \
          throw;                                                                        \
        }                                                                               \
      },                                                                                \
      exception_type)
