option(DP_BUILD_TESTS "Build the test suites" ON)
option(DP_BUILD_BENCH "Build the benchmarks" ON)
option(DP_BUILD_UI "Build the Qt studio (ui/, diffphoton-studio, Qt tests)" ON)
option(DP_SANITIZE "Build with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
