# Precompiled headers and sanitizers.
#
# Most of a geardyn translation unit's compile time is parsing Eigen, GoogleTest and
# nlohmann/json (≈ 3–6 s each at -O2 on the CI machine; measured in docs/benchmarks.md "Build and
# CI time"), so every library and the test suite precompile them once.
# GEARDYN_SANITIZE=address,undefined builds everything of a build directory (libraries, command,
# tests) with ASan and UBSan; any report aborts the test that triggered it. CI and run-tests.sh use
# the cheaper GEARDYN_SANITIZED_TWINS instead (cmake/sanitized_twin/, docs/sanitizers.md).

option(GEARDYN_PRECOMPILED_HEADERS "Precompile the third-party headers (faster builds)" ON)
set(GEARDYN_SANITIZE "" CACHE STRING
    "Comma-separated -fsanitize= list for every target (e.g. address,undefined); empty = none")

if(GEARDYN_SANITIZE)
  add_compile_options(-fsanitize=${GEARDYN_SANITIZE} -fno-omit-frame-pointer
                      -fno-sanitize-recover=all)
  add_link_options(-fsanitize=${GEARDYN_SANITIZE})
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    # GCC's sanitizer instrumentation makes -Wmaybe-uninitialized report libstdc++'s own
    # std::regex and std::function internals (GCC 12, -O1 -fsanitize=address); ASan and UBSan
    # check the actual accesses at run time.
    target_compile_options(geardyn_warnings INTERFACE -Wno-maybe-uninitialized)
  endif()
endif()

# The headers nearly every library translation unit includes, and the Eigen decompositions that
# are compiled once in geardyn::core instead of in every translation unit (extern templates:
# geardyn/numerics/eigen_instantiations.hpp).
set(GEARDYN_PCH_LIBRARY_HEADERS
    <Eigen/Dense> <Eigen/Sparse> <geardyn/numerics/eigen_instantiations.hpp> <algorithm> <array>
    <cmath> <complex> <functional> <limits> <memory> <numbers> <optional> <sstream> <stdexcept>
    <string> <utility> <vector>)
# The tests add GoogleTest, GoogleMock and the JSON library of the command-line tests.
set(GEARDYN_PCH_TEST_HEADERS ${GEARDYN_PCH_LIBRARY_HEADERS} <gmock/gmock.h> <gtest/gtest.h>
    <nlohmann/json.hpp> <filesystem> <fstream> <regex>)

# geardyn_precompile_headers(<target> <header>...): a private precompiled header for <target>.
function(geardyn_precompile_headers target)
  if(GEARDYN_PRECOMPILED_HEADERS)
    target_precompile_headers(${target} PRIVATE ${ARGN})
  endif()
endfunction()

# geardyn_reuse_precompiled_headers(<target> <from>): <target> uses <from>'s precompiled header
# (same compiler flags and definitions; GCC ignores a header that does not match).
function(geardyn_reuse_precompiled_headers target from)
  if(GEARDYN_PRECOMPILED_HEADERS)
    target_precompile_headers(${target} REUSE_FROM ${from})
  endif()
endfunction()
