// What the fuzz targets assert: a broken property stops the fuzzer with a message and a crash
// (so that libFuzzer saves the input), whatever the build type.
#pragma once

#include <cstdio>
#include <cstdlib>

#define SPDFIT_FUZZ_CHECK(condition)                                                              \
  do {                                                                                            \
    if (!(condition)) {                                                                           \
      std::fprintf(stderr, "%s:%d: fuzz property violated: %s\n", __FILE__, __LINE__, #condition); \
      std::abort();                                                                               \
    }                                                                                             \
  } while (false)
