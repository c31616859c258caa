// libFuzzer target mesh_tables (fuzz_entries.hpp: FuzzMeshTables); built with
// GEARDYN_BUILD_FUZZERS=ON and run by scripts/run-fuzzers.sh (docs/fuzzing.md).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "fuzz/fuzz_entries.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    geardyn::fuzz::FuzzMeshTables(data, size);
  } catch (const std::exception& e) {
    // Anything but a normal return (the entry already accepted InvalidInput) breaks the contract:
    // print what escaped and abort so that libFuzzer saves the input.
    std::fprintf(stderr, "mesh_tables: contract broken: %s\n", e.what());
    std::abort();
  } catch (...) {
    std::fprintf(stderr, "%s: contract broken: a non-std exception escaped\n", "mesh_tables");
    std::abort();
  }
  return 0;
}
