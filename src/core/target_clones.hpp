// Hot loops left to the compiler's vectoriser are compiled for AVX2 and for baseline x86-64, the
// one to run picked at load time. Put the attribute on a function defined in one .cpp file only:
// a declaration with target_clones in a header would make every includer emit its own resolver.
#pragma once

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define LFCAM_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define LFCAM_CLONES
#endif
