# libFuzzer needs clang: every target is built with coverage instrumentation so the fuzzers see
# the paths they open in the core; only the fuzz targets link libFuzzer's main.
if(DP_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "DP_FUZZ needs clang (configure with -DCMAKE_CXX_COMPILER=clang++)")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
