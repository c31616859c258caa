// The translation unit that builds the test suite's precompiled header (tests/CMakeLists.txt);
// it defines nothing (main comes from gtest_main).
